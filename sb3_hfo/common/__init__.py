"""Shared helpers of sb3_hfo: skill routers, the action layout read from a space, domain adapters, the mirror and a
small hybrid-action test environment. None of them imports hfo2d (HFO's facts: :mod:`sb3_hfo.hfo`)."""

from sb3_hfo.common.routers import ROUTERS, FieldHalfRouter, SingleSkillRouter, SkillRouter, make_router

__all__ = ["ROUTERS", "FieldHalfRouter", "SingleSkillRouter", "SkillRouter", "make_router"]
