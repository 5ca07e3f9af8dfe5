"""Which part of a HybridPPO policy's exploration noise costs goals: greedy games against sampled ones, split.

PPO improves the policy it samples from; the figures that count play it greedily. For a model with a hand-coded
router (``rl_from_clone.py``'s), this plays the same episodes four ways on ``--env``: greedy (the most likely
discrete action, the parameters' means), the discrete action sampled with the parameters at their means, the
discrete action greedy with the parameters sampled from their Gaussians, and both sampled (the policy PPO trains).
Each mode plays ``--episodes`` episodes on 16 batched games seeded ``--seed`` ... ``--seed + 15`` (the same start
states for every mode), with the torch seed reset before each mode; it prints one JSON line per mode (goal rate,
Wilson interval, end statuses) and writes them to ``--json``.

    python benchmarks/noise_split.py ~/runs/fromclone/v_pull1_s0/final.zip --episodes 400 --seed 0
    python benchmarks/noise_split.py --smoke   # a few seconds: what the test runs (an untrained policy)
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import torch as th

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the sibling script's summary

from hybrid_ppo_runs import batched_episodes  # noqa: E402

from sb3_hfo.hybrid_ppo import HybridPPO  # noqa: E402
from sb3_hfo.vec_env import make_hfo_vec_env  # noqa: E402

#: (name, sample the discrete action, sample the parameters)
MODES: tuple[tuple[str, bool, bool], ...] = (
    ("greedy", False, False),
    ("discrete_sampled", True, False),
    ("parameters_sampled", False, True),
    ("both_sampled", True, True),
)


def act(model: HybridPPO, obs: np.ndarray, sample_discrete: bool, sample_parameters: bool) -> np.ndarray:
    """Env actions for a batch of observations, each half of the hybrid action greedy or sampled."""
    policy = model.policy
    with th.no_grad():
        obs_tensor, _ = policy.obs_to_tensor(obs)
        distribution = policy.action_distribution(obs_tensor)
        discrete_mode, parameters_mode = distribution.mode()
        discrete_sample, parameters_sample = distribution.sample()
        discrete = discrete_sample if sample_discrete else discrete_mode
        parameters = parameters_sample if sample_parameters else parameters_mode
        internal = th.cat([discrete.unsqueeze(-1).to(parameters.dtype), parameters], dim=-1)
    return policy.adapter.to_env(internal.cpu().numpy())


def play(model: HybridPPO, env_id: str, episodes: int, seed: int, mode: tuple[str, bool, bool]) -> dict:
    """``episodes`` episodes of one mode on up to 16 batched games; the summary of ``goal_rate_summary``."""
    _, sample_discrete, sample_parameters = mode
    return batched_episodes(
        lambda obs: act(model, obs, sample_discrete, sample_parameters), env_id, {}, episodes, seed
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", nargs="?", help="a HybridPPO zip with a hand-coded router (or one skill)")
    parser.add_argument("--env", default="HFO/Keeper-v1")
    parser.add_argument("--episodes", type=int, default=400)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path, help="write the four rows here")
    parser.add_argument("--smoke", action="store_true", help="an untrained policy, 4 episodes per mode")
    args = parser.parse_args(argv)
    if args.smoke:
        env = make_hfo_vec_env(args.env, 2, seed=args.seed, monitor=False)
        model = HybridPPO("MlpPolicy", env, seed=args.seed, policy_kwargs={"net_arch": [16]})
        env.close()
        args.episodes = 4
    elif args.model is None:
        parser.error("give a model (or --smoke)")
    else:
        model = HybridPPO.load(args.model, device="cpu")
    if args.episodes < 1:
        parser.error(f"--episodes must be >= 1, got {args.episodes}")
    if model.policy.learned_router:
        parser.error("a learned router samples its skill too; this script splits hand-routed policies only")
    rows = []
    for mode in MODES:
        th.manual_seed(args.seed)
        row = {"mode": mode[0], "model": args.model, "env_id": args.env, "seed": args.seed}
        row.update(play(model, args.env, args.episodes, args.seed, mode))
        print(json.dumps(row), flush=True)
        rows.append(row)
    if args.json is not None:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
