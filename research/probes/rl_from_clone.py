"""Reinforcement learning from the cloned E6 actor: can reward improve the imitation of a scripted striker?

The committed ``e6_imitation`` model (named ``e6`` until 2026-12-05; ``zoo_configs/keeper_v1_skills_cloned_striker.yml``) is the skills actor
taught by DAgger to play like ``hfo2d.strikers.soft_dribble``; its critic was never trained. This probe starts
SkillDDPG from that actor on ``HFO/Keeper-v1`` and first trains the critic alone (the actor's learning rate is 0
for the first ``--critic-warmup`` fraction of the run), so that the actor's first gradients come from a critic
that has seen the cloned policy's returns, then trains both with a small actor learning rate. A periodic greedy
evaluation keeps the best checkpoint; step 0 is the cloned actor itself.

    python research/probes/rl_from_clone.py --steps 200000 --out runs/rl_from_clone --seed 0
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch as th
from stable_baselines3.common.callbacks import EvalCallback
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.monitor import Monitor
from stable_baselines3.common.noise import NormalActionNoise

import hfo2d  # noqa: F401  (registers the envs)
from sb3_hfo import SkillDDPG
from sb3_hfo.callbacks import HFOEpisodeStatsCallback
from sb3_hfo.models import MODELS_DIR, load_model


class AnchoredSkillDDPG(SkillDDPG):
    """SkillDDPG whose actor ascends ``lambda * Q(s, mu(s)) - ||mu(s) - mu_clone(s)||^2``, with ``lambda = alpha /
    mean |Q|`` over the minibatch: TD3+BC's regulariser (Fujimoto & Gu 2021) with the frozen cloned actor's action in
    place of the dataset's, so that the critic's gradient can move the actor only where it outweighs the distance
    from the clone. Uses the autograd update (the fast update knows no such term)."""

    def __init__(self, *args, anchor_alpha: float, **kwargs) -> None:  # noqa: ANN002, ANN003
        super().__init__(*args, fast_update=False, **kwargs)
        self.anchor_alpha = anchor_alpha
        self.anchor_actor: th.nn.Module | None = None

    def _actor_value(self, obs: th.Tensor, actions: th.Tensor) -> tuple[th.Tensor, th.Tensor]:
        value, actor_q = super()._actor_value(obs, actions)
        assert self.anchor_actor is not None
        with th.no_grad():
            anchor = self.anchor_actor.forward(obs, self.policy.route(obs))
            scale = self.anchor_alpha / value.abs().mean().clamp_min(1e-6)
        distance = (actions - anchor).square().sum(dim=1, keepdim=True)
        return scale * value - distance, actor_q


def delayed_rate(rate: float, warmup: float):  # noqa: ANN201  (an SB3 schedule)
    """An SB3 schedule (progress_remaining 1 -> 0): 0 for the first ``warmup`` of the run, ``rate`` after."""

    def schedule(progress_remaining: float) -> float:
        return 0.0 if progress_remaining > 1.0 - warmup else rate

    return schedule


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", type=Path, default=MODELS_DIR / "e6_imitation.zip")
    parser.add_argument("--steps", type=int, default=200_000)
    parser.add_argument(
        "--critic-warmup", type=float, default=0.25, help="fraction of the run with actor lr 0"
    )
    parser.add_argument("--actor-lr", type=float, default=1e-5)
    parser.add_argument("--critic-lr", type=float, default=1e-3)
    parser.add_argument("--epsilon", type=float, default=0.05)
    parser.add_argument("--noise", type=float, default=0.05)
    parser.add_argument("--gamma", type=float, default=0.99)
    parser.add_argument("--eval-freq", type=int, default=10_000, help="steps per env between evaluations")
    parser.add_argument("--eval-episodes", type=int, default=100)
    parser.add_argument(
        "--anchor-alpha",
        type=float,
        default=0.0,
        help="> 0: keep the actor near the clone (TD3+BC's alpha; 2.5 there); 0: plain SkillDDPG",
    )
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("runs/rl_from_clone"))
    args = parser.parse_args()
    th.set_num_threads(1)
    args.out.mkdir(parents=True, exist_ok=True)

    cloned = load_model(args.model, device="cpu", buffer_size=1)
    env = make_vec_env("HFO/Keeper-v1", n_envs=4, seed=args.seed)
    extra = {"anchor_alpha": args.anchor_alpha} if args.anchor_alpha > 0 else {}
    model = (AnchoredSkillDDPG if args.anchor_alpha > 0 else SkillDDPG)(
        "HFOPolicy",
        env,
        learning_rate_actor=delayed_rate(args.actor_lr, args.critic_warmup),
        learning_rate_critic=args.critic_lr,
        buffer_size=300_000,
        learning_starts=10_000,
        batch_size=128,
        tau=1e-3,
        gamma=args.gamma,
        exploration_initial_eps=args.epsilon,
        exploration_final_eps=args.epsilon,
        exploration_keep_parameters=True,
        action_noise=NormalActionNoise(np.zeros(8), args.noise * np.ones(8)),
        mc_mixing=0.2,
        policy_kwargs=dict(cloned.policy_kwargs),
        tensorboard_log=str(args.out / "tb"),
        seed=args.seed,
        verbose=0,
        **extra,
    )
    # the cloned actor, online and target
    model.policy.actor.load_state_dict(cloned.policy.actor.state_dict())
    model.policy.actor_target.load_state_dict(cloned.policy.actor.state_dict())
    if isinstance(model, AnchoredSkillDDPG):
        model.anchor_actor = cloned.policy.actor.requires_grad_(False)
    # SB3 plays uniformly random actions before learning_starts: let the cloned actor play from the first step
    # (the actor is frozen during the critic's warm-up anyway)
    model.learning_starts = 0
    eval_env = Monitor(gym.make("HFO/Keeper-v1"))
    eval_env.reset(seed=args.seed + 10_000)  # seeds the evaluation episodes' random stream
    evaluation = EvalCallback(
        eval_env,
        n_eval_episodes=args.eval_episodes,
        eval_freq=args.eval_freq,
        best_model_save_path=str(args.out),
        log_path=str(args.out),
        deterministic=True,
        verbose=1,
    )
    model.learn(args.steps, callback=[HFOEpisodeStatsCallback(), evaluation], progress_bar=False)
    model.save(args.out / "final_model.zip")
    data = np.load(args.out / "evaluations.npz")
    successes = data["successes"].mean(axis=1).tolist() if "successes" in data else []
    summary = {
        "timesteps": data["timesteps"].tolist(),
        "success_rate": successes,
        "args": {key: str(value) if isinstance(value, Path) else value for key, value in vars(args).items()},
    }
    (args.out / "summary.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
