"""The goal region as OMPL samples it (planners.goals.goal_sample, what GoalBox.sampleGoal
writes): every goal sample is a pose the goal accepts, and a goal of several yaw windows
(issue 24: a set of acceptable poses, e.g. a part that may leave either side down) is sampled
in each window in proportion to its width. The reference is the goal's own ``contains`` and
the windows' widths."""

from __future__ import annotations

import math

import numpy as np

from feeders.scene import Goal
from planners.goals import goal_sample


def _samples(goal: Goal, n: int) -> np.ndarray:
    rng = np.random.default_rng(3)
    return np.array([goal_sample(goal, rng) for _ in range(n)])


def test_one_window_samples_lie_in_the_goal():
    goal = Goal(-0.5, 0.5, -3.0, -2.0, -math.pi / 2, 0.3)
    poses = _samples(goal, 500)
    assert all(goal.contains(tuple(p)) for p in poses)
    assert poses[:, 2].min() < -math.pi / 2 - 0.25 and poses[:, 2].max() > -math.pi / 2 + 0.25


def test_two_windows_are_sampled_in_proportion_to_their_widths():
    goal = Goal(-0.5, 0.5, -3.0, -2.0, 0.0, 0.2, more_yaws=((math.pi, 0.6),))
    poses = _samples(goal, 4000)
    assert all(goal.contains(tuple(p)) for p in poses)
    near_pi = np.abs(np.abs(poses[:, 2]) - math.pi) <= 0.6 + 1e-9
    assert abs(near_pi.mean() - 0.75) < 0.03  # widths 0.4 and 1.2: three quarters at pi
