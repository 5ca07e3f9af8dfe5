"""Demonstrations from a scripted striker in the replay buffer before training (an option beyond the paper).

:class:`DemonstrationPrefillCallback` plays ``episodes`` episodes of one of :mod:`hfo2d.strikers`' scripted
strikers in the training envs when training starts and stores their transitions in the model's replay buffer, as
SB3's own rollout collection would store the agent's (scaled actions, terminal observations, time-limit flags).
The agent's own experience then replaces them first-in first-out. The strikers read only the observation, so the
demonstrations are what the same env would have produced under that policy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import torch as th
import torch.nn.functional as F
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.utils import polyak_update
from stable_baselines3.common.vec_env import VecEnv
from tqdm.auto import tqdm

from hfo2d.strikers import STRIKERS, make_striker
from sb3_hfo.hfo import HFO_ACTION_PARAMETER_SIZES, HFO_KICK_ACTION, HFO_N_DISCRETE_ACTIONS
from sb3_hfo.skill_ddpg.acting import CriticChoice, format_acting


class DemonstrationPrefillCallback(BaseCallback):
    """Fill the replay buffer with ``episodes`` episodes of the scripted striker ``striker`` before training.

    Args:
        striker: a name of :data:`hfo2d.strikers.STRIKERS`.
        episodes: episodes to store (at least 1), counted over all training envs.
        verbose: 1 prints the demonstrations' goal rate.

    Needs envs with HFOEnv's ``"flat"`` action format and observations in the paper's layout (the strikers' input).
    """

    def __init__(self, striker: str = "soft_dribble", episodes: int = 200, verbose: int = 0) -> None:
        super().__init__(verbose)
        if striker not in STRIKERS:
            raise ValueError(f"striker must be one of {tuple(STRIKERS)}, got {striker!r}")
        if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 1:
            raise ValueError(f"episodes must be an integer >= 1, got {episodes!r}")
        self.striker = striker
        self.episodes = episodes
        self.goals = 0
        self.stored = 0

    def _on_training_start(self) -> None:
        env = self.training_env
        model = self.model
        strikers = [make_striker(self.striker) for _ in range(env.num_envs)]
        obs = env.reset()
        finished = 0
        while finished < self.episodes:
            actions = np.stack([striker(o) for striker, o in zip(strikers, obs, strict=True)])
            new_obs, rewards, dones, infos = env.step(actions)
            next_obs = new_obs.copy()
            for i, done in enumerate(dones):
                if done:
                    next_obs[i] = infos[i]["terminal_observation"]
                    strikers[i].reset()
                    finished += 1
                    self.goals += bool(infos[i].get("is_success", False))
            model.replay_buffer.add(obs, next_obs, model.policy.scale_action(actions), rewards, dones, infos)
            self.stored += env.num_envs
            obs = new_obs
        # training starts from fresh episodes, as after SB3's own _setup_learn
        model._last_obs = env.reset()
        model._last_episode_starts = np.ones((env.num_envs,), dtype=bool)
        if self.verbose:
            print(
                f"demonstrations: {finished} episodes of {self.striker} ({self.stored} transitions), "
                f"{self.goals / finished:.1%} goals"
            )
        self.logger.record("demonstrations/goal_rate", self.goals / finished)

    def _on_step(self) -> bool:
        return True


# --- Cloning a scripted striker (DAgger) -----------------------------------------------------------------------

#: The actor's preferences are tanh outputs in [-1, 1]; the cross-entropy that teaches the expert's discrete action
#: reads them times this factor as logits, so that a preference gap of 2 can reach a choice probability near 1.
PREFERENCE_LOGIT_SCALE = 5.0
#: Parameter targets are clipped to this magnitude: a tanh output reaches +-1 only at infinite pre-activation, and
#: the strikers kick at full power (+1 on the action scale).
PARAMETER_TARGET_LIMIT = 0.97


@dataclass(frozen=True)
class CloningRound:
    """One round of :func:`clone_striker`.

    ``goal_rate`` and ``episodes`` are those of the episodes played in this round: by the striker in round 0, by
    the greedy actor (as fitted in the round before) afterwards. ``transitions`` is the dataset's size after the
    round and ``loss`` the mean loss of the last epoch of the fit that followed it (``nan`` after the last round,
    which is not followed by a fit).
    """

    round: int
    episodes: int
    goal_rate: float
    transitions: int
    loss: float


def _play_round(
    model: Any,
    env: VecEnv,
    striker: str,
    episodes: int,
    expert_acts: bool,
    progress: Any | None,
) -> tuple[np.ndarray, np.ndarray, int]:
    """Play ``episodes`` episodes in ``env`` (split over its envs as SB3's ``evaluate_policy`` does, so that short
    episodes are not over-counted) and label every visited observation with the striker's action.

    Returns (observations, the striker's actions on the policy's [-1, 1] scale, goals)."""
    n_envs = env.num_envs
    targets = np.array([(episodes + i) // n_envs for i in range(n_envs)])
    counts = np.zeros(n_envs, dtype=int)
    strikers = [make_striker(striker) for _ in range(n_envs)]
    observations: list[np.ndarray] = []
    labels: list[np.ndarray] = []
    goals = 0
    obs = env.reset()
    state = None
    episode_starts = np.ones(n_envs, dtype=bool)
    while (counts < targets).any():
        expert = np.stack([s(o) for s, o in zip(strikers, obs, strict=True)])
        active = counts < targets
        observations.append(obs[active])
        labels.append(expert[active])
        if expert_acts:
            actions = expert
        else:
            actions, state = model.predict(obs, state=state, episode_start=episode_starts, deterministic=True)
        obs, _, dones, infos = env.step(actions)
        episode_starts = dones
        for i in np.flatnonzero(dones):
            strikers[i].reset()
            if counts[i] < targets[i]:
                counts[i] += 1
                goals += bool(infos[i].get("is_success", False))
                if progress is not None:
                    progress.update(1)
    scaled = model.policy.scale_action(np.concatenate(labels)).astype(np.float32)
    return np.concatenate(observations).astype(np.float32), scaled, goals


def _fit_actor(
    policy: Any,
    observations: np.ndarray,
    targets: np.ndarray,
    epochs: int,
    batch_size: int,
    learning_rate: float,
    kick_weight: float,
    generator: th.Generator,
) -> float:
    """Fit the actor to the striker's actions: cross-entropy on the discrete action plus the absolute error of the
    parameters of the striker's discrete action (the striker's direction targets jump, e.g. when its far-post aim
    flips side; an absolute error follows one side where a squared error would average the two). Fresh Adam with a
    cosine-decayed step size; returns the last epoch's mean loss."""
    device = policy.device
    obs = th.as_tensor(observations, device=device)
    target = th.as_tensor(targets, device=device)
    kind = target[:, :HFO_N_DISCRETE_ACTIONS].argmax(dim=1)  # the striker's actions are one-hot (Command)
    weights = th.zeros_like(target)
    start = HFO_N_DISCRETE_ACTIONS
    for action, size in enumerate(HFO_ACTION_PARAMETER_SIZES):
        scale = kick_weight if action == HFO_KICK_ACTION else 1.0
        weights[kind == action, start : start + size] = scale
        start += size
    target = target.clamp(-PARAMETER_TARGET_LIMIT, PARAMETER_TARGET_LIMIT)
    actor = policy.actor
    optimizer = th.optim.Adam(actor.parameters(), lr=learning_rate)
    schedule = th.optim.lr_scheduler.CosineAnnealingLR(optimizer, epochs)
    policy.set_training_mode(True)
    n = obs.shape[0]
    epoch_loss = float("nan")
    for _ in range(epochs):
        order = th.randperm(n, generator=generator).to(device)
        total = 0.0
        for begin in range(0, n, batch_size):
            rows = order[begin : begin + batch_size]
            batch = obs[rows]
            out = actor(batch, policy.route(batch))
            choice_loss = F.cross_entropy(
                out[:, :HFO_N_DISCRETE_ACTIONS] * PREFERENCE_LOGIT_SCALE, kind[rows]
            )
            parameter_loss = ((out - target[rows]).abs() * weights[rows]).sum(dim=1).mean()
            loss = choice_loss + parameter_loss
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            total += loss.item() * rows.shape[0]
        schedule.step()
        epoch_loss = total / n
    policy.set_training_mode(False)
    return epoch_loss


def clone_striker(
    model: Any,
    striker: str = "soft_dribble",
    rounds: int = 8,
    episodes_per_round: int = 300,
    epochs: int = 20,
    batch_size: int = 256,
    learning_rate: float = 1e-3,
    kick_weight: float = 5.0,
    seed: int | None = None,
    env: VecEnv | None = None,
    progress_bar: bool = False,
    verbose: int = 0,
) -> list[CloningRound]:
    """Teach ``model``'s actor to play like one of :mod:`hfo2d.strikers`' scripted strikers, by DAgger.

    Round 0 plays ``episodes_per_round`` episodes with the striker; each following round fits the actor (from where
    it is) to every observation seen so far labelled with the striker's action, then plays as many episodes with
    the greedy actor, labelling what it visits. The learner so sees the striker's actions in the states its own
    mistakes lead to, which plain cloning of the striker's episodes never shows it. The actor's target network is
    synchronised at the end; the critic is not trained.

    This is imitation of a hand-written policy, not learning from reward: results obtained with it are labelled so
    (docs/results.md, the committed model ``e6_imitation``).

    Args:
        model: a :class:`~sb3_hfo.SkillDDPG` with an :class:`~sb3_hfo.HFOPolicy` whose actor picks the discrete
            action (no :class:`~sb3_hfo.skill_ddpg.acting.CriticChoice` in its ``acting``: the critic is not trained
            here, so it cannot choose).
        striker: a name of :data:`hfo2d.strikers.STRIKERS`.
        rounds: rounds after round 0 (fits of the actor), at least 1.
        episodes_per_round: episodes played per round, at least 1.
        epochs: passes over the aggregated data per fit, at least 1.
        batch_size: minibatch size of the fit.
        learning_rate: Adam's initial step size in each fit (decayed to 0 over its epochs).
        kick_weight: weight of KICK's parameters in the parameter loss (DASH and TURN weigh 1): a shot's power and
            direction decide a goal more than a dash's.
        seed: seeds the envs of each round (``seed + round``) and the minibatch order; default the model's seed
            (0 if it has none), so that an rl-zoo3 run's ``--seed`` decides it.
        env: the VecEnv to play in; default ``model.get_env()``. Needs HFOEnv's ``"flat"`` action format and the
            paper's observation layout (the strikers' input).
        progress_bar: show a tqdm bar over all episodes.
        verbose: 1 prints one line per round.

    Returns:
        one :class:`CloningRound` per round, round 0 first; the last one's ``goal_rate`` is the returned actor's.
    """
    policy = getattr(model, "policy", None)
    if not hasattr(policy, "route") or not hasattr(policy, "acting"):
        raise TypeError(f"model must be a SkillDDPG with an HFOPolicy, got {type(model).__name__}")
    if any(isinstance(strategy, CriticChoice) for strategy in policy.acting):
        raise ValueError(
            "clone_striker needs an actor that picks the discrete action: acting without 'critic' (the critic is "
            f"not trained by cloning), got acting {format_acting(policy.acting)!r}"
        )
    if striker not in STRIKERS:
        raise ValueError(f"striker must be one of {tuple(STRIKERS)}, got {striker!r}")
    for name, value in (
        ("rounds", rounds),
        ("episodes_per_round", episodes_per_round),
        ("epochs", epochs),
        ("batch_size", batch_size),
    ):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    for name, value in (("learning_rate", learning_rate), ("kick_weight", kick_weight)):
        if (
            isinstance(value, bool)
            or not isinstance(value, (int, float))
            or not math.isfinite(value)
            or value <= 0
        ):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if seed is None:
        seed = model.seed if isinstance(model.seed, int) and model.seed >= 0 else 0
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    env = model.get_env() if env is None else env
    if env is None:
        raise ValueError("the model has no env: pass env= (a VecEnv)")
    action_dim = int(np.prod(env.action_space.shape))
    expected_dim = HFO_N_DISCRETE_ACTIONS + sum(HFO_ACTION_PARAMETER_SIZES)
    if action_dim != expected_dim:
        raise ValueError(
            f"the env's action must be HFOEnv's flat action ({expected_dim} entries), got {action_dim}"
        )

    generator = th.Generator().manual_seed(seed)
    progress = tqdm(total=(rounds + 1) * episodes_per_round, desc="clone_striker") if progress_bar else None
    history: list[CloningRound] = []
    obs_parts: list[np.ndarray] = []
    label_parts: list[np.ndarray] = []
    for round_index in range(rounds + 1):
        if round_index > 0:
            loss = _fit_actor(
                policy,
                np.concatenate(obs_parts),
                np.concatenate(label_parts),
                epochs,
                batch_size,
                learning_rate,
                kick_weight,
                generator,
            )
            previous = history[-1]
            history[-1] = CloningRound(
                previous.round, previous.episodes, previous.goal_rate, previous.transitions, loss
            )
        env.seed(seed + round_index)
        observations, labels, goals = _play_round(
            model, env, striker, episodes_per_round, expert_acts=round_index == 0, progress=progress
        )
        obs_parts.append(observations)
        label_parts.append(labels)
        transitions = sum(part.shape[0] for part in obs_parts)
        history.append(
            CloningRound(round_index, episodes_per_round, goals / episodes_per_round, transitions, math.nan)
        )
        if verbose:
            who = striker if round_index == 0 else "greedy actor"
            print(
                f"clone_striker round {round_index}: {who} scored {goals / episodes_per_round:.1%} "
                f"of {episodes_per_round} episodes; {transitions} labelled observations"
            )
    if progress is not None:
        progress.close()
    polyak_update(policy.actor.parameters(), policy.actor_target.parameters(), 1.0)
    return history


class StrikerCloningCallback(BaseCallback):
    """Run :func:`clone_striker` on the model in its training envs when training starts (for rl-zoo3 configs).

    Each round's figures are logged under ``cloning/`` (``goal_rate``, ``transitions``, ``loss``; the logger's step
    is the round). With ``train_after=False`` training stops at its first step, so that the saved model is the
    cloned actor; with ``True`` reinforcement learning goes on from it.

    Args:
        train_after: go on training after cloning.
        verbose: 1 prints one line per round.
        **cloning: :func:`clone_striker`'s arguments (``striker``, ``rounds``, ``episodes_per_round``, ``epochs``,
            ``batch_size``, ``learning_rate``, ``kick_weight``, ``seed``, ``progress_bar``).
    """

    def __init__(self, train_after: bool = False, verbose: int = 0, **cloning: Any) -> None:
        super().__init__(verbose)
        if not isinstance(train_after, bool):
            raise ValueError(f"train_after must be True or False, got {train_after!r}")
        unknown = set(cloning) - {
            "striker", "rounds", "episodes_per_round", "epochs", "batch_size", "learning_rate", "kick_weight",
            "seed", "progress_bar",
        }  # fmt: skip
        if unknown:
            raise ValueError(f"unknown clone_striker arguments {sorted(unknown)}")
        self.train_after = train_after
        self.cloning = cloning
        self.history: list[CloningRound] = []

    def _on_training_start(self) -> None:
        self.history = clone_striker(self.model, env=self.training_env, verbose=self.verbose, **self.cloning)
        for entry in self.history:
            self.logger.record("cloning/goal_rate", entry.goal_rate)
            self.logger.record("cloning/transitions", entry.transitions)
            if not math.isnan(entry.loss):
                self.logger.record("cloning/loss", entry.loss)
            self.logger.dump(step=entry.round)
        # training goes on from fresh episodes, as after SB3's own _setup_learn
        self.model._last_obs = self.training_env.reset()
        self.model._last_episode_starts = np.ones((self.training_env.num_envs,), dtype=bool)

    def _on_step(self) -> bool:
        return self.train_after
