"""Train with rl-zoo3: ``python -m sb3_hfo.train --algo skill_ddpg --env HFO/EmptyGoal-v0 --conf-file ...``.

Every rl-zoo3 ``train.py`` option works (``-n``, ``--seed``, ``--hyperparams``, ``--eval-freq``,
``--tensorboard-log``, ``-P``, ``-optimize``, ``--storage``, ``--study-name``, ...; see ``--help``). The wrapper
exists because rl-zoo3 builds its ``--algo`` choices before importing ``--gym-packages``: it registers
``skill_ddpg`` (and its Optuna sampler) and the HFO environments first, defaults ``--algo`` to ``skill_ddpg``
and ``--num-threads`` to 1 (small networks: more torch threads only contend for the cores) and then calls
``rl_zoo3.train.train()``. A missing ``--conf-file`` or an unknown ``--env`` is reported in one line.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence


def _option_value(args: Sequence[str], *names: str) -> str | None:
    """Value of the last ``--name value`` / ``--name=value`` among ``args`` (None when absent)."""
    value = None
    for index, arg in enumerate(args):
        name, sep, inline = arg.partition("=")
        if name in names:
            value = inline if sep else (args[index + 1] if index + 1 < len(args) else None)
    return value


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's training entry point with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``."""
    args = list(sys.argv[1:] if argv is None else argv)
    if not any(arg in ("-h", "--help") for arg in args):
        if _option_value(args, "-conf", "--conf-file") is None:
            # rl-zoo3 would otherwise look for hyperparams/skill_ddpg.yml inside its own package.
            sys.exit("error: --conf-file is required, e.g. --conf-file zoo_configs/e1_empty_goal_fast.yml")
        env_id = _option_value(args, "--env")
        if env_id is not None:
            import gymnasium as gym

            from sb3_hfo.zoo import hfo_env_ids

            known = hfo_env_ids()
            if env_id not in gym.registry:
                sys.exit(f"error: unknown env id {env_id!r}; registered HFO ids: {', '.join(known)}")

    import rl_zoo3.train

    from sb3_hfo.zoo import run_rl_zoo_entry_point

    run_rl_zoo_entry_point(rl_zoo3.train.train, args, playback=False, single_thread=True)


if __name__ == "__main__":
    main()
