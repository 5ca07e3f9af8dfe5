"""benchmarks/noise_split.py: a HybridPPO policy played greedy, with its discrete choice or its parameters sampled."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import torch as th

from sb3_hfo.hybrid_ppo import HybridPPO
from sb3_hfo.vec_env import make_hfo_vec_env

REPO = Path(__file__).resolve().parents[2]
_SPEC = importlib.util.spec_from_file_location("noise_split", REPO / "benchmarks" / "noise_split.py")
noise_split = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(noise_split)


def test_each_half_of_the_action_is_greedy_or_sampled_as_asked() -> None:
    env = make_hfo_vec_env("HFO/Keeper-v1", 8, seed=0, monitor=False)
    model = HybridPPO(
        "MlpPolicy", env, seed=0, policy_kwargs={"skills": 2, "router": "field_half", "domain": "hfo"}
    )
    obs = env.reset()
    env.close()
    greedy = noise_split.act(model, obs, False, False)
    assert np.array_equal(greedy, model.predict(obs, deterministic=True)[0])
    adapter = model.policy.adapter
    th.manual_seed(0)
    discrete_only = adapter.from_env(noise_split.act(model, obs, True, False))
    th.manual_seed(0)
    parameters_only = adapter.from_env(noise_split.act(model, obs, False, True))
    greedy_internal = adapter.from_env(greedy)
    # an untrained policy's categorical is near uniform: some sampled choices differ, its parameters are the means
    assert not np.array_equal(discrete_only[:, 0], greedy_internal[:, 0])
    read = adapter.parameter_mask[discrete_only[:, 0].astype(int)].astype(bool)
    assert np.allclose(
        discrete_only[:, 1:][read], mean_parameters(model, obs, discrete_only[:, 0])[read], atol=1e-5
    )
    # the parameters sampled (std 1 at log std 0), the discrete choice greedy
    assert np.array_equal(parameters_only[:, 0], greedy_internal[:, 0])
    read = adapter.parameter_mask[greedy_internal[:, 0].astype(int)].astype(bool)
    assert not np.allclose(parameters_only[:, 1:][read], greedy_internal[:, 1:][read], atol=1e-3)


def mean_parameters(model: HybridPPO, obs: np.ndarray, discrete: np.ndarray) -> np.ndarray:
    """The greedy parameters (the means, clipped to the env's bounds as an action) under the given choices."""
    with th.no_grad():
        distribution = model.policy.action_distribution(model.policy.obs_to_tensor(obs)[0])
        internal = th.cat([th.as_tensor(discrete).unsqueeze(-1), distribution.mean], dim=-1).numpy()
    return model.policy.adapter.from_env(model.policy.adapter.to_env(internal))[:, 1:]


def test_smoke_run_writes_the_four_modes(tmp_path: Path) -> None:
    out = tmp_path / "split.json"
    command = [sys.executable, str(REPO / "benchmarks" / "noise_split.py"), "--smoke", "--json", str(out)]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert completed.returncode == 0, completed.stderr[-2000:]
    rows = json.loads(out.read_text())
    assert [row["mode"] for row in rows] == [mode[0] for mode in noise_split.MODES]
    assert all(row["episodes"] == 4 == sum(row["status"].values()) for row in rows)
    refused = subprocess.run(
        [sys.executable, str(REPO / "benchmarks" / "noise_split.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert refused.returncode == 2 and "give a model" in refused.stderr
