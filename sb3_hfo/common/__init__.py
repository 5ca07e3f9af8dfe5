"""Shared helpers of sb3_hfo: skill routers and a small hybrid-action test environment."""

from sb3_hfo.common.routers import ROUTERS, FieldHalfRouter, SingleSkillRouter, SkillRouter, make_router

__all__ = ["ROUTERS", "FieldHalfRouter", "SingleSkillRouter", "SkillRouter", "make_router"]
