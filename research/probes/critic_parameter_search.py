"""Would the critic's choice score more if it could also nudge the actor's parameters?

With the acting ``CriticChoice`` the agent plays the discrete action its critic values most *at the actor's
parameters*. The session-12 time-outs showed states where the critic valued other parameters (a turn towards the
ball) above the actor's. This benchmark plays the same greedy episodes twice: once as the model acts, once with the
critic choosing among every discrete action at the actor's parameters *and* at the actor's parameters moved by each
of ``--offsets`` (in the policy's [-1, 1] action scale), one parameter at a time, clipped to [-1, 1]. Prints one
line per mode: scoring rate with its 95 % interval and the count of each end status. Used for the session-13 note
in research/RESULTS.md:

    python research/probes/critic_parameter_search.py models/x19_static_keeper_each_action_parameters_seed0 \
        --episodes 1000 --offsets 0.05 0.02
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import torch as th

from sb3_hfo.cli.evaluate import episodes_parser
from sb3_hfo.evaluation import load_for_evaluation, model_n_skills, run_episodes, summarize
from sb3_hfo.skill_ddpg.acting import CriticChoice, format_acting
from sb3_hfo.skill_ddpg.policies import HFO_KICK_ACTION


def searched_candidates(
    policy: Any, actions: th.Tensor, offsets: Sequence[float]
) -> tuple[th.Tensor, th.Tensor]:
    """Every discrete action at the actor's parameters and at each one-parameter move by ``offsets``.

    :param policy: an ``HFOPolicy`` with ``mask_unused_parameters``.
    :param actions: ``(B, action_dim)`` actor outputs in [-1, 1].
    :param offsets: moves to try, each applied with both signs.
    :return: ``candidates (B, C, action_dim)`` as the critic sees them (the played action's one-hot preferences,
        its own parameters, 0 elsewhere) and ``owners (C,)``, the discrete action of each candidate.
    """
    rows, own_masks = policy.discrete_action_rows, policy.own_parameter_masks
    moves = sorted({sign * abs(offset) for offset in offsets for sign in (-1.0, 1.0)} - {0.0})
    candidates, owners = [], []
    for action_index in range(policy.n_discrete_actions):
        played = rows[action_index] + actions * own_masks[action_index]
        candidates.append(played)
        owners.append(action_index)
        for parameter in own_masks[action_index].nonzero().flatten().tolist():
            for move in moves:
                moved = played.clone()
                moved[:, parameter] = (moved[:, parameter] + move).clamp(-1.0, 1.0)
                candidates.append(moved)
                owners.append(action_index)
    return th.stack(candidates, dim=1), th.tensor(owners)


def searched_choice(policy: Any, obs: th.Tensor, actions: th.Tensor, offsets: Sequence[float]) -> th.Tensor:
    """``(B, action_dim)``: the candidate of :func:`searched_candidates` the first critic values most (KICK left out
    where the policy's acting ``KickMask`` rules it out)."""
    candidates, owners = searched_candidates(policy, actions, offsets)
    batch, n_candidates, action_dim = candidates.shape
    values = policy.critic.forward(
        obs.repeat_interleave(n_candidates, dim=0), candidates.view(batch * n_candidates, action_dim)
    ).view(batch, n_candidates)
    no_kick = policy.kick_unavailable(obs)
    if no_kick is not None:
        kick_columns = owners == HFO_KICK_ACTION
        values[:, kick_columns] = values[:, kick_columns].masked_fill(no_kick.unsqueeze(1), -th.inf)
    return candidates[th.arange(batch), values.argmax(dim=1)]


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=1000)
    parser.add_argument(
        "--offsets", type=float, nargs="+", default=[0.05, 0.02], help="parameter moves to try"
    )
    args = parser.parse_args(argv)

    model, env, env_id, env_kwargs, path = load_for_evaluation(args.model, args.env)
    policy = model.policy
    if policy.own_parameter_masks is None:
        parser.error(
            "the model's policy needs mask_unused_parameters (the critic must see one action's parameters)"
        )
    policy.acting = (CriticChoice(), *(s for s in policy.acting if not isinstance(s, CriticChoice)))
    n_skills = model_n_skills(model)
    modes = {
        "actor's parameters": policy.critic_choice,
        f"searched, offsets {args.offsets}": lambda obs, actions: searched_choice(
            policy, obs, actions, args.offsets
        ),
    }
    try:
        for mode, choice in modes.items():
            policy.critic_choice = choice  # what predict calls with the acting CriticChoice
            records = run_episodes(model, env, args.episodes, args.seed, True, n_skills)
            result = summarize(
                records, model=str(path), env_id=env_id, seed=args.seed, deterministic=True, n_skills=n_skills,
                env_kwargs=env_kwargs, acting=format_acting(policy.acting),
            )  # fmt: skip
            low, high = result.scoring_rate_ci95
            counts = " / ".join(f"{status} {count}" for status, count in sorted(result.status_counts.items()))
            print(f"{mode}: {100 * result.scoring_rate:.1f} % [{100 * low:.1f}, {100 * high:.1f}]  {counts}")
    finally:
        env.close()


if __name__ == "__main__":
    main()
