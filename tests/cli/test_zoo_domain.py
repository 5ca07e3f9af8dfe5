"""The zoo gives the HFO env ids HFO's domain adapter, so that configs keep naming field_half, kick_mask and landmarks
without one (issue 33, item 6: the algorithms themselves know no domain)."""

from __future__ import annotations

from sb3_hfo.cli.zoo import HFO_DOMAIN_NAME, with_hfo_domain
from sb3_hfo.common.domain import resolve_domain
from sb3_hfo.hfo import HFO_DOMAIN


def test_hfo_ids_get_hfos_domain_and_a_config_keeps_its_own() -> None:
    assert resolve_domain(HFO_DOMAIN_NAME) is HFO_DOMAIN
    assert with_hfo_domain(None, "HFO/Keeper-v1") == {"domain": "hfo"}
    assert with_hfo_domain({"n_skills": 2}, "HFO/EmptyGoal-v0") == {"domain": "hfo", "n_skills": 2}
    assert with_hfo_domain({"domain": None}, "HFO/EmptyGoal-v0") == {"domain": None}
    assert with_hfo_domain({"n_skills": 2}, "Pendulum-v1") == {"n_skills": 2}
    assert with_hfo_domain(None, "Pendulum-v1") is None
