"""Train with rl-zoo3: ``python -m sb3_hfo.train --algo skill_ddpg --env HFO/EmptyGoal-v0 --conf-file ...``.

``--conf-file`` takes a YAML file, a Python module (as rl-zoo3's does) or the name of a config that comes with
sb3-hfo (``e1_empty_goal_fast``: :mod:`sb3_hfo.cli.configs`, from any folder).

Every rl-zoo3 ``train.py`` option works (``-n``, ``--seed``, ``--hyperparams``, ``--eval-freq``,
``--tensorboard-log``, ``-P``, ``-optimize``, ``--storage``, ``--study-name``, ...; see ``--help``), and two of
its own: ``--checkpoint-freq N`` writes the whole training state (:mod:`sb3_hfo.resume`) to the run folder's
``training_checkpoint.pkl`` every ``N`` steps (``10min``: every 10 minutes), and ``--resume RUN_DIR`` with the run's command line continues that
run from it as if never stopped (same folder, budget and TensorBoard run). The wrapper
exists because rl-zoo3 builds its ``--algo`` choices before importing ``--gym-packages``: it registers
``skill_ddpg`` (and its Optuna sampler) and the HFO environments first, defaults ``--algo`` to ``skill_ddpg``
and ``--num-threads`` to 1 (small networks: more torch threads only contend for the cores) and then calls
``rl_zoo3.train.train()``. A user's mistake (a missing ``--conf-file`` or ``--env``, an unknown ``--env``, bad
``--env-kwargs``, a negative ``--seed``, a bad option) is reported in one line, exit code 2.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from sb3_hfo.cli.configs import with_named_config
from sb3_hfo.cli.errors import (
    UserError,
    check_installed,
    check_train_args,
    fail,
    one_line_argparse_errors,
)
from sb3_hfo.cli.zoo import (
    ConfigConflictError,
    ResumeError,
    run_rl_zoo_entry_point,
    split_checkpoint_options,
)

PROG = "python -m sb3_hfo.train"


def main(argv: Sequence[str] | None = None) -> None:
    """Run rl-zoo3's training entry point with SkillDDPG registered; ``argv`` defaults to ``sys.argv[1:]``.

    User errors (see :func:`sb3_hfo.cli.errors.check_train_args`) exit with one line on stderr and code 2.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        args, checkpointing = split_checkpoint_options(args)
    except ValueError as error:
        fail(error)
    try:
        check_installed("zoo", ("rl_zoo3", "optuna"), PROG)
    except UserError as error:
        fail(error)
    args = with_named_config(args)  # --conf-file e1_empty_goal_fast: the config that comes with sb3-hfo
    if not any(arg in ("-h", "--help") for arg in args):
        try:
            check_train_args(args)
        except UserError as error:
            fail(error)

    import rl_zoo3.train

    with one_line_argparse_errors(PROG):
        try:
            run_rl_zoo_entry_point(rl_zoo3.train.train, args, False, True, checkpointing)
        except (ResumeError, ConfigConflictError) as error:
            fail(error)


if __name__ == "__main__":
    main()
