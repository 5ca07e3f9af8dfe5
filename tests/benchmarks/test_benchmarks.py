"""The benchmark scripts run end to end at tiny settings (their figures come from full runs, not from here)."""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_update_throughput_times_every_contestant_at_every_thread_count(tmp_path: Path) -> None:
    out = tmp_path / "throughput.json"
    command = [sys.executable, str(REPO / "benchmarks" / "update_throughput.py"), "--threads", "1", "2"]
    command += ["--updates", "2", "--learn-steps", "2", "--repeats", "1", "--fill", "64", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(out.read_text())
    contestants = {"sb3_ddpg", "skill_ddpg_1_skill", "skill_ddpg_2_skills"}
    assert set(results["by_threads"]) == {"1", "2"}
    for row in results["by_threads"].values():
        assert set(row["train_updates_per_s"]) == contestants
        assert all(rate > 0 for rate in row["learn_steps_per_s"].values())
        assert row["train_ratio_vs_sb3_ddpg"]["sb3_ddpg"] == 1.0
    fastest = results["each_at_its_fastest_thread_count"]
    for name in contestants:
        rate = fastest["train_updates_per_s"][name]
        assert rate == max(row["train_updates_per_s"][name] for row in results["by_threads"].values())
        assert (
            rate
            == results["by_threads"][str(fastest["train_updates_threads"][name])]["train_updates_per_s"][name]
        )


def test_update_throughput_rejects_a_zero_thread_count(tmp_path: Path) -> None:
    command = [sys.executable, str(REPO / "benchmarks" / "update_throughput.py"), "--threads", "0"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert completed.returncode == 2 and "--threads must be >= 1" in completed.stderr


def test_python_vs_cli_times_both_with_the_same_thread_count(tmp_path: Path) -> None:
    out = tmp_path / "python_vs_cli.json"
    command = [sys.executable, str(REPO / "benchmarks" / "python_vs_cli.py"), "--steps", "3"]
    command += ["--no-default-threads", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(out.read_text())
    assert set(results["steps_per_s"]) == {"python", "cli"}
    assert all(sample["steps"] == 3 for runs in results["samples"].values() for sample in runs)
    assert results["threads"] == {"python": [1], "cli": [1]}  # learn chose the CLI's count by itself
    assert results["ratio_python_vs_cli"] == results["steps_per_s"]["python"] / results["steps_per_s"]["cli"]


def test_the_default_run_leaves_the_research_tests_out() -> None:
    """research/tests (the probes of particular models) run on demand, ``pytest research/tests``; a plain
    ``pytest`` collects only tests/."""
    completed = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-p", "no:cacheprovider"],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=REPO,
    )
    assert completed.returncode == 0, completed.stdout[-2000:]
    # one line per test (pytest -q) or per file (-qq): the path comes first either way
    collected = [line for line in completed.stdout.splitlines() if ".py::" in line or ".py:" in line]
    assert collected and all(line.startswith("tests/") for line in collected), collected[:5]
    assert (REPO / "research" / "tests" / "test_probes.py").is_file()


def test_training_throughput_times_both_contestants_in_each_round(tmp_path: Path) -> None:
    out = tmp_path / "training_throughput.json"
    command = [sys.executable, str(REPO / "benchmarks" / "training_throughput.py"), "--smoke"]
    command += ["--rounds", "2", "--seconds", "0.2", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(out.read_text())
    samples = results["samples"]
    assert set(samples) == {"hybrid_ppo", "skill_ddpg"}
    assert all(len(runs) == 2 for runs in samples.values())
    for runs in samples.values():
        for sample in runs:
            assert sample["seconds"] >= 0.2 and sample["steps"] > 0  # a slice of at least --seconds
            assert sample["warmup_steps"] > 0  # timed after the warm-up
    # HybridPPO trains on hfo2d's batch of 16 games, SkillDDPG on E6's 4 envs in rl-zoo3's DummyVecEnv
    assert results["n_envs"] == {"hybrid_ppo": 16, "skill_ddpg": 4}
    assert results["vec_env"]["hybrid_ppo"].endswith("HFOVecEnv")
    assert results["vec_env"]["skill_ddpg"] == "DummyVecEnv"
    assert results["torch_threads"] == {"hybrid_ppo": [1], "skill_ddpg": [1]}
    rates = results["steps_per_s"]
    assert results["ratio_hybrid_ppo_vs_skill_ddpg"] == rates["hybrid_ppo"] / rates["skill_ddpg"]
    for name, runs in samples.items():
        assert rates[name] == statistics.median(sample["steps_per_s"] for sample in runs)
    assert "load average" in results["uptime_before"] and results["cpu_model"]


def test_training_throughput_takes_the_papers_e6_config_for_skill_ddpg(tmp_path: Path) -> None:
    out = tmp_path / "training_throughput.json"
    command = [
        sys.executable,
        str(REPO / "benchmarks" / "training_throughput.py"),
        "--smoke",
        "--rounds",
        "1",
    ]
    command += ["--seconds", "0.2", "--out", str(out)]
    command += ["--skill-ddpg-config", str(REPO / "zoo_configs" / "e6_keeper_skills.yml")]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(out.read_text())
    assert results["skill_ddpg_config"] == "zoo_configs/e6_keeper_skills.yml"
    assert results["n_envs"]["skill_ddpg"] == 1  # the paper's recipe: one env
    wrong = subprocess.run(
        [*command[:-1], str(REPO / "zoo_configs" / "e1_empty_goal.yml")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert wrong.returncode == 2 and "has no HFO/Keeper-v1 section" in wrong.stderr


def test_training_throughput_profile_shows_where_hybrid_ppo_spends_its_time(tmp_path: Path) -> None:
    command = [sys.executable, str(REPO / "benchmarks" / "training_throughput.py"), "--profile"]
    completed = subprocess.run(
        [*command, "--profile-rollouts", "1"], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    # one rollout of 16 games x 256 steps
    assert "HybridPPO on HFO/Keeper-v1: 4,096 steps" in completed.stdout
    for function in ("collect_rollouts", "step_games", "(train)"):
        assert function in completed.stdout


def test_hybrid_ppo_runs_smoke_writes_curve_run_record_and_final_model(tmp_path: Path) -> None:
    """CI's tiny version of the E6 experiment: a curriculum run on the batched Keeper-v1, evaluated greedily."""
    out = tmp_path / "e6"
    command = [
        sys.executable,
        str(REPO / "benchmarks" / "hybrid_ppo_runs.py"),
        "e6",
        "--smoke",
        "--out",
        str(out),
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    rows = [json.loads(line) for line in (out / "curve.jsonl").read_text().splitlines()]
    assert [row["final"] for row in rows] == [False, False, True]
    assert [row["steps"] for row in rows] == [1024, 2048, 2048]
    for row in rows:
        evaluation = row["eval"]
        assert sum(evaluation["status"].values()) == evaluation["episodes"] == 4
        assert evaluation["goals"] == evaluation["status"].get("GOAL", 0)
    record = json.loads((out / "run.json").read_text())
    assert record["env_id"] == "HFO/Keeper-v1" and record["curriculum"] == [0.0, 1.0, 0.5]
    assert "reward" in record["method"] and "imitation" in record["method"]
    assert (out / "final.zip").is_file()
    # a second run into the same folder would mix two curves: refused
    again = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert again.returncode == 2 and "already holds a run" in again.stderr
    # --init continues from the run's final weights: the first evaluation plays them
    init = tmp_path / "e6_continued"
    continued = [*command[:-1], str(init), "--init", str(out / "final.zip"), "--curriculum", "none"]
    completed = subprocess.run(continued, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    record = json.loads((init / "run.json").read_text())
    assert record["init"] == str(out / "final.zip") and record["curriculum"] is None


def test_core_scaling_times_one_process_and_several_side_by_side() -> None:
    command = [sys.executable, str(REPO / "benchmarks" / "core_scaling.py"), "--seconds", "0.2"]
    completed = subprocess.run([*command, "--processes", "2"], capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr[-2000:]
    results = json.loads(completed.stdout.splitlines()[-1])
    assert len(results["side_by_side"]) == 2 and len(results["alone"]) == 1
    assert all(row["steps_per_s"] > 0 for rows in results.values() for row in rows)
    refused = subprocess.run([*command, "--processes", "0"], capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and "--processes >= 1" in refused.stderr


def test_team_speed_counts_the_cpu_of_descendant_processes() -> None:
    """team_speed.py compares the real HFO's CPU per cycle, spread over its processes, with hfo2d's: the /proc
    reader must find a grandchild's CPU time (bin/HFO starts rcssserver and the NPCs below itself)."""
    sys.path.insert(0, str(REPO / "benchmarks"))
    try:
        import team_speed
    finally:
        sys.path.remove(str(REPO / "benchmarks"))
    spin = "import time; end = time.process_time() + 0.4\nwhile time.process_time() < end: pass\nprint('done', flush=True)\ninput()"
    grandparent = (
        f"import subprocess, sys; child = subprocess.Popen([sys.executable, '-c', {spin!r}]); child.wait()"
    )
    process = subprocess.Popen(
        [sys.executable, "-c", grandparent], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    try:
        assert process.stdout is not None and process.stdout.readline().strip() == "done"
        assert team_speed.descendant_cpu_seconds() >= 0.3  # the grandchild, still alive, spun 0.4 s
        assert team_speed.descendant_cpu_seconds(process.pid) >= 0.3
        assert team_speed.descendant_cpu_seconds(1 << 30) == 0.0  # no such process: nothing below it
    finally:
        process.communicate("\n", timeout=30)


def test_hybrid_ppo_runs_e6_carry_is_e6_with_the_carry_reward_and_the_full_goalie(tmp_path: Path) -> None:
    """The ``e6_carry`` preset (research/e6_from_reward.md Part D) changes only the reward and drops the goalie
    curriculum; ``e6`` itself is untouched. Its smoke run trains against the full goalie (no keeper_skill)."""
    sys.path.insert(0, str(REPO / "benchmarks"))
    try:
        import hybrid_ppo_runs
    finally:
        sys.path.remove(str(REPO / "benchmarks"))
    e6, carry = hybrid_ppo_runs.PRESETS["e6"], hybrid_ppo_runs.PRESETS["e6_carry"]
    assert e6["env_kwargs"] == {"reward": "shaped_gap_refund"} and e6["curriculum"] == (0.0, 1.0, 0.5)
    assert carry["env_kwargs"] == {"reward": "carry"} and carry["curriculum"] is None
    assert {k: v for k, v in carry.items() if k not in ("env_kwargs", "curriculum")} == {
        k: v for k, v in e6.items() if k not in ("env_kwargs", "curriculum")
    }
    out = tmp_path / "e6_carry"
    command = [
        sys.executable,
        str(REPO / "benchmarks" / "hybrid_ppo_runs.py"),
        "e6_carry",
        "--smoke",
        "--out",
    ]
    completed = subprocess.run(
        [*command, str(out)], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    record = json.loads((out / "run.json").read_text())
    assert record["env_kwargs"] == {"reward": "carry"} and record["curriculum"] is None
    rows = [json.loads(line) for line in (out / "curve.jsonl").read_text().splitlines()]
    assert rows[-1]["final"] and "keeper_skill" not in rows[-1]


def test_hybrid_ppo_runs_stop_at_cuts_the_run_but_keeps_the_schedule_over_the_step_budget(
    tmp_path: Path,
) -> None:
    """``--stop-at`` ends a leg at a step count while the learning rate still decays over the step budget: the
    smoke budget is 2,048 steps in rollouts of 1,024, so a run stopped at 1,536 has trained once, at
    progress_remaining 1 - 1024 / 2048 = 0.5 (a run whose budget were 1,536 would be at 1 - 1024 / 1536)."""
    from sb3_hfo.hybrid_ppo import HybridPPO

    out = tmp_path / "stopped"
    command = [sys.executable, str(REPO / "benchmarks" / "hybrid_ppo_runs.py"), "e6_carry", "--smoke"]
    completed = subprocess.run(
        [*command, "--out", str(out), "--stop-at", "1536"],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    rows = [json.loads(line) for line in (out / "curve.jsonl").read_text().splitlines()]
    assert [(row["steps"], row["final"]) for row in rows] == [(1024, False), (1536, True)]
    record = json.loads((out / "run.json").read_text())
    assert record["steps"] == 2048 and record["stop_at"] == 1536
    model = HybridPPO.load(out / "final.zip", device="cpu")
    assert model.num_timesteps == 1536 and model._current_progress_remaining == 0.5
    # a cap beyond the step budget is refused before anything is written
    refused = tmp_path / "refused"
    completed = subprocess.run(
        [*command, "--out", str(refused), "--stop-at", "4096"],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert completed.returncode == 2 and "--stop-at must lie in (0, 2048]" in completed.stderr
    assert not refused.exists()


def test_hybrid_ppo_runs_reset_log_std_reopens_exploration_of_a_continued_policy(tmp_path: Path) -> None:
    """``--reset-log-std V`` with ``--init`` sets the loaded heads' log standard deviations to V and keeps the means;
    without ``--init`` it is refused."""
    from sb3_hfo.hybrid_ppo import HybridPPO

    sys.path.insert(0, str(REPO / "benchmarks"))
    try:
        import hybrid_ppo_runs
    finally:
        sys.path.remove(str(REPO / "benchmarks"))
    command = [sys.executable, str(REPO / "benchmarks" / "hybrid_ppo_runs.py"), "e6_carry", "--smoke"]
    first = tmp_path / "first"
    completed = subprocess.run(
        [*command, "--out", str(first), "--stop-at", "1024"], capture_output=True, text=True, timeout=300
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    trained = HybridPPO.load(first / "final.zip", device="cpu")
    before = {name: value.clone() for name, value in trained.policy.state_dict().items()}
    assert hybrid_ppo_runs.reset_log_std(trained, -2.0) == 1
    for name, value in trained.policy.state_dict().items():
        if name.endswith("log_std"):
            assert (value == -2.0).all() and not (before[name] == -2.0).all()
        else:
            assert (value == before[name]).all(), name
    # through the command line: the continued run starts from the loaded means with the new deviations
    continued = tmp_path / "continued"
    completed = subprocess.run(
        [*command, "--out", str(continued), "--init", str(first / "final.zip"), "--reset-log-std", "-2.0"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert json.loads((continued / "run.json").read_text())["reset_log_std"] == -2.0
    log_std = HybridPPO.load(continued / "final.zip", device="cpu").policy.heads[0].log_std
    # two smoke updates move it by at most ~0.04 (80 Adam steps of 5e-4); the preset starts at -0.5
    assert (log_std - (-2.0)).abs().max() < 0.1
    refused = subprocess.run(
        [*command, "--out", str(tmp_path / "refused"), "--reset-log-std", "-2.0"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert refused.returncode == 2 and "needs --init" in refused.stderr


def test_capture_split_tells_a_carry_into_the_goalie_from_a_saved_shot(tmp_path: Path) -> None:
    """benchmarks/capture_split.py: the split's rule on hand-made episodes, and a short run end to end."""
    sys.path.insert(0, str(REPO / "benchmarks"))
    try:
        import capture_split
    finally:
        sys.path.remove(str(REPO / "benchmarks"))
    touch = {"power": 10.0, "distance_m": 6.0, "ball_speed": 0.5, "step": 40, "cycles_before_end": 2}
    shot = {**touch, "power": 90.0, "ball_speed": 2.2}
    carried = {"status": "CAPTURED_BY_DEFENSE", "agent_ball_m": 1.1, "ball_goal_m": 5.0, "last_kick": touch}
    saved = {"status": "CAPTURED_BY_DEFENSE", "agent_ball_m": 3.5, "ball_goal_m": 3.0, "last_kick": shot}
    near_shot = {**saved, "agent_ball_m": 1.5}  # still within the carry radius: on the ball
    goal = {"status": "GOAL", "agent_ball_m": 5.0, "ball_goal_m": 0.0, "last_kick": shot}
    assert capture_split.capture_kind(carried) == "on_the_ball"
    assert capture_split.capture_kind(saved) == "after_a_shot"
    assert capture_split.capture_kind(near_shot) == "on_the_ball"
    summary = capture_split.summarize([carried, saved, near_shot, goal])
    assert summary["goals"] == 1 and summary["status"] == {"CAPTURED_BY_DEFENSE": 3, "GOAL": 1}
    assert {name: kind["episodes"] for name, kind in summary["by_kind"].items()} == {
        "goal": 1,
        "on_the_ball": 2,
        "after_a_shot": 1,
    }
    assert summary["by_kind"]["after_a_shot"]["last_kick_ball_speed_bins"] == {"1.8-2.4": 1}
    # end to end on an untrained model: every episode is played and counted once
    from sb3_hfo.hybrid_ppo import HybridPPO
    from sb3_hfo.vec_env import make_hfo_vec_env

    env = make_hfo_vec_env("HFO/Keeper-v1", 2, seed=0)
    HybridPPO("MlpPolicy", env, n_steps=64, batch_size=64, seed=0).save(tmp_path / "untrained.zip")
    env.close()
    out = tmp_path / "split.json"
    completed = subprocess.run(
        [
            sys.executable,
            str(REPO / "benchmarks" / "capture_split.py"),
            str(tmp_path / "untrained.zip"),
            "--episodes",
            "6",
            "--env-kwargs",
            '{"frames_per_trial": 40}',
            "--json",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    result = json.loads(out.read_text())
    assert result["episodes"] == 6 and sum(result["status"].values()) == 6


def test_hybrid_ppo_runs_part_e_presets_change_one_thing_each(tmp_path: Path) -> None:
    """``e6_carry_shot`` changes only ``e6_carry``'s reward, ``e6_carry_sd`` only its policy's deviations
    (research/e6_from_reward.md Part E); a state-dependent policy may start from a state-independent one's weights
    (``--init``), acting as it did, while any other architecture mismatch is refused."""
    import pytest
    import torch as th

    from sb3_hfo.hybrid_ppo import HybridPPO
    from sb3_hfo.vec_env import make_hfo_vec_env

    sys.path.insert(0, str(REPO / "benchmarks"))
    try:
        import hybrid_ppo_runs
    finally:
        sys.path.remove(str(REPO / "benchmarks"))
    carry, shot, sd = (hybrid_ppo_runs.PRESETS[name] for name in ("e6_carry", "e6_carry_shot", "e6_carry_sd"))
    assert shot["env_kwargs"] == {"reward": "carry_shot"}
    assert {k: v for k, v in shot.items() if k != "env_kwargs"} == {
        k: v for k, v in carry.items() if k != "env_kwargs"
    }
    assert sd["hp"]["policy_kwargs"] == {**carry["hp"]["policy_kwargs"], "state_dependent_std": True}
    assert {k: v for k, v in sd.items() if k != "hp"} == {k: v for k, v in carry.items() if k != "hp"}

    env = make_hfo_vec_env("HFO/Keeper-v1", 2, seed=0)
    fixed = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, seed=0, policy_kwargs={"net_arch": [16]})
    fixed.save(tmp_path / "fixed.zip")
    varying = HybridPPO(
        "MlpPolicy",
        env,
        n_steps=16,
        batch_size=32,
        seed=1,
        policy_kwargs={"net_arch": [16], "state_dependent_std": True},
    )
    hybrid_ppo_runs.load_policy_weights(varying, tmp_path / "fixed.zip")
    obs = env.reset()
    for model in (fixed, varying):
        model.policy.set_training_mode(False)
    with th.no_grad():
        want = fixed.policy.action_distribution(th.as_tensor(obs))
        got = varying.policy.action_distribution(th.as_tensor(obs))
    assert th.equal(got.mean, want.mean) and th.equal(got.log_std, want.log_std)
    wider = HybridPPO("MlpPolicy", env, n_steps=16, batch_size=32, seed=0, policy_kwargs={"net_arch": [32]})
    with pytest.raises((ValueError, RuntimeError)):
        hybrid_ppo_runs.load_policy_weights(wider, tmp_path / "fixed.zip")
    env.close()
