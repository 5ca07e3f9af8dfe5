"""What a greedy agent does in its OUT_OF_TIME episodes: the critic's values at the last steps.

Plays ``--episodes`` greedy episodes with the critic picking the discrete action (episode ``i`` reset with seed
``--seed + i``) and, for each that ends OUT_OF_TIME, prints its action counts and its last ``--last`` steps: the
action played, the critic's value of DASH / TURN / KICK at the actor's parameters, the actor's turn (degrees), the
critic's value of turning straight towards the ball instead, and the distance to the ball (m). Used for the
session-12 analysis in research/RESULTS.md:

    python research/probes/time_out_trace.py models/x15_static_keeper_relative_kick_seed0 --episodes 300
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from typing import Any

import numpy as np
import torch as th

from hfo2d.action_layout import HFO_FLAT_ACTION_LAYOUT
from hfo2d.features import BALL_ANGLE_COS, BALL_ANGLE_SIN
from hfo2d.hfo_env import TURN
from sb3_hfo.cli.evaluate import episodes_parser
from sb3_hfo.evaluation import load_for_evaluation
from sb3_hfo.skill_ddpg.acting import CriticChoice

#: The turn direction's index in HFO's flat action ([-1, 1] for [-180, 180] degrees).
TURN_DIRECTION_INDEX = HFO_FLAT_ACTION_LAYOUT.action_direction(TURN)


def step_values(model: Any, obs: np.ndarray) -> tuple[np.ndarray, float, float]:
    """(Q of DASH / TURN / KICK at the actor's parameters, the actor's turn in degrees, Q of turning to the ball)."""
    policy = model.policy
    observation = th.as_tensor(np.asarray(obs, dtype=np.float32)[None])
    with th.no_grad():
        actions = policy.actor.forward(observation, policy.route(observation))
        candidates, values = policy.discrete_values(observation, actions)
        towards_ball = candidates[:, TURN].clone()
        bearing = math.atan2(float(obs[BALL_ANGLE_SIN]), float(obs[BALL_ANGLE_COS]))
        towards_ball[0, TURN_DIRECTION_INDEX] = math.degrees(bearing) / 180.0
        turn_to_ball = policy.critic.forward(observation, policy.critic_action(towards_ball)).item()
    return values[0].numpy(), float(actions[0, TURN_DIRECTION_INDEX]) * 180.0, turn_to_ball


def main(argv: Sequence[str] | None = None) -> None:
    parser = episodes_parser(__doc__.splitlines()[0], default_episodes=300)
    parser.add_argument("--last", type=int, default=3, help="steps printed at the end of each time-out")
    args = parser.parse_args(argv)

    model, env, _, _, _ = load_for_evaluation(args.model, args.env)
    # the critic picks the discrete action; the model's other acting strategies are kept
    model.policy.acting = (
        CriticChoice(),
        *(s for s in model.policy.acting if not isinstance(s, CriticChoice)),
    )
    time_outs = 0
    try:
        for episode in range(args.episodes):
            obs, info = env.reset(seed=args.seed + episode)
            trace = []
            done = False
            while not done:
                values, turn_deg, turn_to_ball = step_values(model, obs)
                obs, _, terminated, truncated, info = env.step(model.predict(obs, deterministic=True)[0])
                player, ball = info["player"], info["ball"]
                distance = math.dist(player[:2], ball[:2])
                trace.append((info["action"], values, turn_deg, turn_to_ball, distance))
                done = bool(terminated or truncated)
            if info["status"] != "OUT_OF_TIME":
                continue
            time_outs += 1
            print(f"episode {episode}: OUT_OF_TIME, actions {dict(Counter(step[0] for step in trace))}")
            for action, values, turn_deg, turn_to_ball, distance in trace[-args.last :]:
                print(
                    f"  {action:<4} Q(dash, turn, kick) {np.round(values, 2)}  turn {turn_deg:+6.1f} deg  "
                    f"Q(turn to ball) {turn_to_ball:5.2f}  ball {distance:5.1f} m"
                )
    finally:
        env.close()
    print(f"{time_outs} OUT_OF_TIME of {args.episodes} episodes")


if __name__ == "__main__":
    main()
