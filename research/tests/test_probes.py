"""The research probes (research/probes/) run end to end at tiny settings on the committed models.

Not part of the default test run (pyproject's testpaths is tests/): ``pytest research/tests``. A probe whose model
is not committed (sb3_hfo/pretrained/manifest.json) is skipped with the reason.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PROBES = REPO / "research" / "probes"


def committed(name: str) -> str:
    """``name`` when it is a committed model (sb3_hfo/pretrained/manifest.json); the test is skipped otherwise."""
    from sb3_hfo.models import read_manifest

    if name not in read_manifest():
        pytest.skip(f"model {name!r} is not committed (sb3_hfo/pretrained/manifest.json)")
    return name


def test_discrete_choice_runs_both_modes_on_the_committed_model(tmp_path: Path) -> None:
    command = [sys.executable, str(PROBES / "discrete_choice.py")]
    command += [committed("e1_skill_pdqn"), "--episodes", "2", "--seed", "0"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    lines = completed.stdout.splitlines()
    assert [line.split()[0] for line in lines] == ["actor", "critic"]
    assert all("scoring rate" in line for line in lines)


def test_discrete_choice_agreement_counts_every_step(tmp_path: Path) -> None:
    command = [sys.executable, str(PROBES / "discrete_choice.py")]
    command += [
        committed("e3"),
        "--episodes",
        "2",
        "--agreement",
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    rows = [line for line in completed.stdout.splitlines() if line.startswith("agreement: actor prefers")]
    shares = [float(row.split()[-1].rstrip("%")) for row in rows]
    assert rows and abs(sum(shares) - 100.0) < 0.1 * len(rows)
    summary = completed.stdout.splitlines()[-1]
    assert summary.startswith("agreement: ") and "steps, the played action" in summary


def test_failure_map_groups_episodes_by_start_and_writes_a_png(tmp_path: Path) -> None:
    out = tmp_path / "map.png"
    command = [sys.executable, str(PROBES / "failure_map.py")]
    command += [committed("e1_skill_pdqn"), "--episodes", "6", "--out", str(out)]
    completed = subprocess.run(
        [*command, "--acting", "critic,kick_mask,mirror"],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert "(better of state and mirror image) picks" in completed.stdout.splitlines()[0]
    rows = [line for line in completed.stdout.splitlines() if "episodes  goal rate" in line]
    totals = [index for index, row in enumerate(rows) if row.split()[:2] == ["all", "6"]]
    assert len(totals) == 2  # one table by start, one by where the ball ended
    for first, last in ((0, totals[0]), (totals[0] + 1, totals[1])):
        assert sum(int(row.split("episodes")[0].split()[-1]) for row in rows[first:last]) == 6  # all classed
    assert all(
        row.split()[:3] == ["ball", "ends", "in"] or "GOAL" not in row for row in rows[totals[0] + 1 : -1]
    )
    assert out.stat().st_size > 10_000


def test_start_class_bands_the_agents_lead_over_the_ball() -> None:
    sys.path.insert(0, str(PROBES))
    try:
        from failure_map import start_class
    finally:
        sys.path.pop(0)
    from sb3_hfo.evaluation import EpisodeRecord

    def record(agent_x: float) -> EpisodeRecord:
        return EpisodeRecord("GOAL", 1, 0.0, 0, [], 0, [1], None, (10.0, 0.0), (agent_x, 3.0))

    assert start_class(record(2.0)).startswith("agent > 5 m behind")
    assert start_class(record(12.0)).startswith("agent within 5 m")
    assert start_class(record(20.0)).startswith("agent 5-15 m ahead")
    assert start_class(record(30.0)).startswith("agent > 15 m ahead")
    assert start_class(EpisodeRecord("GOAL", 1, 0.0, 0, [], 0, [1])) == "unknown"


def test_mirror_twin_tables_both_sides_by_start_class(tmp_path: Path) -> None:
    out = tmp_path / "twin.json"
    command = [sys.executable, str(PROBES / "mirror_twin.py")]
    command += [committed("e1_skill_pdqn"), "--episodes", "5"]
    completed = subprocess.run(
        [*command, "--json", str(out)], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert [line.split()[0] for line in completed.stdout.splitlines()[-4:]] == [
        "mirror",
        "mirror",
        "agent",
        "all",
    ]
    tables = json.loads(out.read_text())
    for side in ("plain", "twin"):
        classes = [counts for name, counts in tables[side].items() if name != "all"]
        assert sum(c["episodes"] for c in classes) == tables[side]["all"]["episodes"] == 5
        assert sum(c["goals"] for c in classes) == tables[side]["all"]["goals"]


def test_mirror_start_class_follows_hfos_offsets() -> None:
    sys.path.insert(0, str(PROBES))
    try:
        from mirror_twin import START_CLASSES, mirror_start_class
    finally:
        sys.path.pop(0)
    from sb3_hfo.evaluation import EpisodeRecord

    def record(ball_y: float, agent_y: float) -> EpisodeRecord:
        return EpisodeRecord("GOAL", 1, 0.0, 0, [], 0, [1], None, (5.0, ball_y), (10.0, agent_y))

    assert mirror_start_class(record(0.0, 15.0)) == START_CLASSES[0]  # o = 1: mirror -15 is drawn with o = -2
    assert mirror_start_class(record(0.0, -5.0)) == START_CLASSES[1]  # o = -1: mirror +5 is never drawn
    assert mirror_start_class(record(-10.0, 15.0)) == START_CLASSES[1]  # o = 2: mirror -25 is never drawn
    assert mirror_start_class(record(20.0, 27.2)) == START_CLASSES[2]  # clamped at the side line


def test_end_class_sorts_goals_by_goal_half_and_losses_by_distance() -> None:
    sys.path.insert(0, str(PROBES))
    try:
        from failure_map import end_class, end_class_labels, table_rows
    finally:
        sys.path.pop(0)
    from sb3_hfo.evaluation import EpisodeRecord

    def record(status: str, x: float, y: float) -> EpisodeRecord:
        return EpisodeRecord(status, 1, 0.0, 0, [], 0, [1], end_ball=(x, y))

    assert end_class(record("GOAL", 53.0, -3.0)) == "ball ends in the goal, top half (y < 0)"
    assert end_class(record("GOAL", 53.0, 0.0)) == "ball ends in the goal, bottom half (y >= 0)"
    assert end_class(record("CAPTURED_BY_DEFENSE", 52.0, 3.0)) == "ball ends 0-5 m from goal"
    assert end_class(record("CAPTURED_BY_DEFENSE", 47.0, 1.0)) == "ball ends 5-10 m from goal"
    assert end_class(record("OUT_OF_BOUNDS", 42.4, 0.0)) == "ball ends 10-20 m from goal"
    assert end_class(record("OUT_OF_TIME", 30.0, 0.0)) == "ball ends >= 20 m from goal"
    assert end_class(EpisodeRecord("GOAL", 1, 0.0, 0, [], 0, [1])) == "unknown"
    records = [
        record("OUT_OF_TIME", 30.0, 0.0),
        record("CAPTURED_BY_DEFENSE", 52.0, 3.0),
        record("GOAL", 53, 1),
    ]
    names = [row[0] for row in table_rows(records, end_class)]
    assert names == [end_class_labels()[i] for i in (1, 2, 5)] + ["all"]  # nearest the goal first


def test_weight_layout_times_both_layouts_of_every_shape() -> None:
    command = [sys.executable, str(PROBES / "weight_layout.py"), "--calls", "2"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr[-2000:]
    lines = completed.stdout.splitlines()
    assert len(lines) == 7 and all("transposed: forward" in line for line in lines[:6])
    assert lines[-1].startswith("sum of the three products")


def test_critic_kick_scan_reports_both_outcomes_and_writes_a_png(tmp_path: Path) -> None:
    out = tmp_path / "scan.png"
    model = REPO / "sb3_hfo" / "pretrained" / f"{committed('e3')}.zip"
    command = [sys.executable, str(PROBES / "critic_kick_scan.py"), str(model), "--labels", "x3"]
    command += ["--episodes", "8", "--out", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    rows = {line.split()[0]: line.split() for line in completed.stdout.splitlines() if line.startswith("  ")}
    assert {"GOAL", "CAPTURED_BY_DEFENSE"} <= set(rows)
    assert sum(int(rows[outcome][1]) for outcome in ("GOAL", "CAPTURED_BY_DEFENSE")) <= 8
    assert out.stat().st_size > 10_000


def test_critic_kick_scan_asks_the_critic_at_goalie_bearing_plus_offset() -> None:
    import gymnasium as gym
    import numpy as np
    import torch as th

    from sb3_hfo import SkillDDPG

    sys.path.insert(0, str(PROBES))
    try:
        import critic_kick_scan as scan
    finally:
        sys.path.pop(0)
    model = SkillDDPG("HFOPolicy", gym.make("HFO/StaticKeeper-v0"), policy_kwargs=dict(net_arch=[8]), seed=0)
    seen: list[th.Tensor] = []
    original = model.policy.critic.forward

    def recording_forward(obs: th.Tensor, action: th.Tensor) -> th.Tensor:
        seen.append(action.clone())
        return original(obs, action)

    model.policy.critic.forward = recording_forward  # type: ignore[method-assign]
    obs = np.zeros(66, dtype=np.float32)
    obs[scan.GOALIE_BEARING_SIN], obs[scan.GOALIE_BEARING_COS] = (
        np.sin(np.radians(170)),
        np.cos(np.radians(170)),
    )
    profile, _ = scan.scan_shot(model, obs)
    (kicks,) = seen
    assert profile.shape == scan.OFFSETS_DEG.shape and profile.max() == 0.0
    assert th.equal(kicks[:, :3], th.tensor([[-1.0, -1.0, 1.0]]).expand(len(kicks), 3))
    expected = (170 + scan.OFFSETS_DEG + 180) % 360 - 180  # wraps past +180 degrees
    # Compared on the circle: +180 and -180 degrees are one direction, and which one float rounding gives at the
    # wrap differs between CPUs (-180 on Intel, 179.99998 on AMD EPYC).
    difference = (kicks[:, scan.KICK_DIRECTION_INDEX].numpy() * 180 - expected + 180) % 360 - 180
    np.testing.assert_allclose(difference, 0.0, atol=1e-4)


def test_shot_aim_projects_kicks_onto_the_goal_line_and_reports_outcomes() -> None:
    import math

    sys.path.insert(0, str(PROBES))
    try:
        import shot_aim
    finally:
        sys.path.pop(0)
    assert shot_aim.goal_line_y(40.0, 0.0, math.atan2(3.0, 12.5)) == pytest.approx(3.0)
    assert shot_aim.goal_line_y(40.0, -2.0, 0.0) == pytest.approx(-2.0)
    assert math.isnan(shot_aim.goal_line_y(40.0, 0.0, math.pi))  # away from the goal

    model = REPO / "sb3_hfo" / "pretrained" / f"{committed('e3')}.zip"
    command = [sys.executable, str(PROBES / "shot_aim.py"), str(model), "--episodes", "10"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=REPO)
    assert completed.returncode == 0, completed.stderr[-2000:]
    outcome_lines = [line for line in completed.stdout.splitlines() if line.startswith(("GOAL:", "CAPTURED"))]
    assert len(outcome_lines) == 2, completed.stdout
    counts = [int(line.split()[1]) for line in outcome_lines if "episodes" in line]
    assert counts and sum(counts) <= 10


def test_parameter_loss_cost_times_both_losses(tmp_path: Path) -> None:
    command = [sys.executable, str(PROBES / "parameter_loss_cost.py")]
    command += ["--updates", "2", "--repeats", "1", "--fill", "300"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    lines = completed.stdout.splitlines()
    assert [line.split(":")[0].strip() for line in lines] == ["chosen", "each_action", "each_action / chosen"]
    assert float(lines[-1].split()[-1]) > 0


def test_time_out_trace_reports_every_time_out(tmp_path: Path) -> None:
    command = [sys.executable, str(PROBES / "time_out_trace.py")]
    command += [
        committed("e3"),
        "--episodes",
        "9",
        "--last",
        "2",
    ]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    lines = completed.stdout.splitlines()
    headers = [line for line in lines if line.startswith("episode ")]
    assert lines[-1] == f"{len(headers)} OUT_OF_TIME of 9 episodes"
    # Two steps printed per time-out (which episodes time out depends on the CPU's float rounding).
    assert sum("Q(turn to ball)" in line for line in lines) == 2 * len(headers)


def test_critic_parameter_search_candidates_move_one_own_parameter_at_a_time() -> None:
    sys.path.insert(0, str(PROBES))
    try:
        import critic_parameter_search
    finally:
        sys.path.pop(0)
    import torch as th

    from sb3_hfo.evaluation import load_for_evaluation

    model, env, _, _, _ = load_for_evaluation(committed("e3"))
    env.close()
    policy = model.policy
    actions = th.rand(4, policy.action_dim, generator=th.Generator().manual_seed(0)) * 2 - 1
    candidates, owners = critic_parameter_search.searched_candidates(policy, actions, [0.1, -0.1, 0.3])
    sizes = policy.action_parameter_sizes
    # Per discrete action: the actor's parameters, then 4 moves (+-0.1, +-0.3) of each of its parameters.
    assert owners.tolist() == [j for j, size in enumerate(sizes) for _ in range(1 + 4 * size)]
    for column, owner in enumerate(owners.tolist()):
        own_mask = policy.own_parameter_masks[owner]
        played = policy.discrete_action_rows[owner] + actions * own_mask
        difference = candidates[:, column] - played
        assert (difference * (1 - own_mask) == 0).all()  # preferences name the owner; others' parameters 0
        assert ((difference != 0).sum(dim=1) <= 1).all()  # one parameter moved
        assert (candidates[:, column].abs() <= 1).all()

    obs = th.zeros(4, policy.observation_space.shape[0])
    chosen = critic_parameter_search.searched_choice(policy, obs, actions, [0.1, -0.1, 0.3])
    values = policy.critic.forward(obs.repeat_interleave(len(owners), 0), candidates.flatten(0, 1)).view(
        4, -1
    )
    best = candidates[th.arange(4), values.argmax(dim=1)]
    assert th.equal(
        chosen, best
    )  # KICK is allowed: the kickable feature of a zero observation is not negative


def test_critic_parameter_search_plays_both_modes(tmp_path: Path) -> None:
    command = [sys.executable, str(PROBES / "critic_parameter_search.py")]
    command += [committed("e3"), "--episodes", "2"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    lines = completed.stdout.splitlines()
    assert [line.split(":")[0] for line in lines] == ["actor's parameters", "searched, offsets [0.05, 0.02]"]


def test_return_by_outcome_groups_every_episode_once_and_replays_them_under_another_reward(
    tmp_path: Path,
) -> None:
    def rows(*extra: str) -> list[dict]:
        out = tmp_path / "rows.json"
        command = [sys.executable, str(PROBES / "return_by_outcome.py")]
        command += [
            committed("e6_keeper_v0"),
            "--episodes",
            "3",
        ]
        command += ["--seed", "0", "--json", str(out), *extra]
        completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
        assert completed.returncode == 0, completed.stderr[-2000:]
        return json.loads(out.read_text())["rows"]

    own, sparse = rows(), rows("--reward", "sparse")
    assert sum(row["episodes"] for row in own) == 3
    assert len({(row["last_kick"], row["status"]) for row in own}) == len(own)
    # the same episodes, scored by the sparse reward: 1 per goal, else 0
    assert [(r["last_kick"], r["status"], r["mean_steps"]) for r in own] == [
        (r["last_kick"], r["status"], r["mean_steps"]) for r in sparse
    ]
    assert all(r["mean_return"] == (1.0 if r["status"] == "GOAL" else 0.0) for r in sparse)


@pytest.mark.parametrize("episodes", ["0", "ten"])
def test_episode_benchmarks_refuse_a_bad_episode_count(tmp_path: Path, episodes: str) -> None:
    command = [sys.executable, str(PROBES / "return_by_outcome.py"), "no_such_model"]
    completed = subprocess.run(
        [*command, "--episodes", episodes], capture_output=True, text=True, timeout=120, cwd=tmp_path
    )
    assert completed.returncode == 2 and "--episodes" in completed.stderr
    assert ("at least 1" if episodes == "0" else "must be an integer") in completed.stderr


def test_rl_from_clone_starts_from_the_cloned_actor_and_reports_each_evaluation(tmp_path: Path) -> None:
    committed("e6_imitation")
    command = [sys.executable, str(PROBES / "rl_from_clone.py"), "--steps", "800", "--eval-freq", "100"]
    command += ["--eval-episodes", "2", "--out", str(tmp_path / "run"), "--seed", "0"]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["timesteps"] == [400, 800]  # 4 envs: an evaluation every 100 steps of each
    assert len(summary["success_rate"]) == 2 and all(0.0 <= rate <= 1.0 for rate in summary["success_rate"])
    assert (tmp_path / "run" / "final_model.zip").is_file()
