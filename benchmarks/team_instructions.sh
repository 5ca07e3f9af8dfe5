#!/bin/bash
# Instructions per cycle of hfo2d's team game (or HFO/Keeper-v1), counted by valgrind's cachegrind: unlike
# cycles per second, the count does not depend on the machine's load, so two versions of the code compare
# exactly on a shared machine (a proxy for CPU time: the same Python code at the same IPC).
#
#   benchmarks/team_instructions.sh ENVS_DIR CONFIG [CYCLES]
#
# Run it in the project's environment (its python must import numpy, gymnasium, pymunk). ENVS_DIR: the envs/ folder of the checkout to measure (e.g. an old commit unpacked with
# `git archive COMMIT envs | tar -x -C /tmp/old`); CONFIG: "keeper" (HFO/Keeper-v1) or OvD (O offense agents
# against D agent2d defense NPCs, e.g. 2v2); CYCLES: default 1000. Random flat actions with seed 0, episode
# resets included; the count of a run of 0 cycles (imports, construction) is subtracted. Hash seed, ASLR, BLAS
# threads and the garbage collector are pinned so that a rerun gives the same count to about 0.01 %.
set -euo pipefail
envs_dir=$1
config=$2
cycles=${3:-1000}
runner=$(mktemp --suffix=.py)
trap 'rm -f "$runner"' EXIT
cat > "$runner" <<'PY'
import gc
import sys

gc.disable()
import numpy as np

config, cycles = sys.argv[1], int(sys.argv[2])
rng = np.random.default_rng(0)
if config == "keeper":
    import gymnasium as gym

    import hfo2d  # noqa: F401

    env = gym.make("HFO/Keeper-v1").unwrapped
    actions = rng.random((max(cycles, 1), 8), dtype=np.float32)
    env.reset(seed=0)
    for index in range(cycles):
        _, _, terminated, truncated, _ = env.step(actions[index])
        if terminated or truncated:
            env.reset()
else:
    from hfo2d.team import TeamGame

    offense, defense = map(int, config.split("v"))
    game = TeamGame(offense_agents=offense, defense_npcs=defense)
    actions = {a.name: rng.random((max(cycles, 1), a.layout.size), dtype=np.float32) for a in game.agents}
    game.reset(seed=0)
    for index in range(cycles):
        _, _, terminated, truncated, _ = game.step({name: a[index] for name, a in actions.items()})
        if terminated or truncated:
            game.reset()
PY
count() {
    OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 PYTHONHASHSEED=0 PYTHONPATH="$envs_dir" \
        setarch -R valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null \
        python "$runner" "$config" "$1" 2>&1 | grep "I *refs" | tr -d ',' | awk '{print $NF}'
}
empty=$(count 0)
full=$(count "$cycles")
echo "$config $(((full - empty) / cycles)) instructions/cycle ($envs_dir, $cycles cycles)"
