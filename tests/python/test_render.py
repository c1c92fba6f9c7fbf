"""Rendering (gpfd.render): render_mode="rgb_array" in gymnasium.make and make_vec, the frames'
shape and content, Gymnasium's recorders, and the way Stable-Baselines3's make_vec_env makes
environments (without SB3 itself)."""

import warnings
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from gymnasium.vector import AsyncVectorEnv, SyncVectorEnv
from gymnasium.wrappers import RecordVideo, RenderCollection

import gpfd  # noqa: F401  (registers the gpfd/ ids)
from conftest import gpfd_env
from gpfd import render
from gpfd.envs import GpfdEnv

IDS = ["gpfd/Acrobot-v0", "gpfd/CartPole-v0", "gpfd/Swimmer-v0", "gpfd/Tetris-v0"]
POLE = (202, 152, 101)  # render.cartpole's colours
LINK = (0, 204, 204)  # render.acrobot's


def rgb(env: gym.Env) -> np.ndarray:
    """env.render(), checked to be a frame."""
    frame = env.render()
    assert isinstance(frame, np.ndarray)
    return frame


def play(env: gym.Env, steps: int, seed: int = 0) -> None:
    env.reset(seed=seed)
    env.action_space.seed(seed)
    for _ in range(steps):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            env.reset()


@pytest.mark.parametrize("env_id", IDS)
def test_rgb_array_frames_are_uint8_images_that_follow_the_state(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    assert env.render_mode == "rgb_array"
    assert env.metadata["render_modes"] == ["rgb_array"]
    assert env.metadata["render_fps"] >= 1
    env.reset(seed=1)
    first = rgb(env)
    assert first.dtype == np.uint8 and first.ndim == 3 and first.shape[2] == 3
    assert np.array_equal(rgb(env), first)  # The same state, the same frame.
    play(env, 5, seed=1)
    later = rgb(env)
    assert later.shape == first.shape
    assert not np.array_equal(later, first)


@pytest.mark.parametrize("env_id", IDS)
def test_check_env_passes_with_rendering(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # test_envs.py checks the warnings; here: no failure.
        check_env(env.unwrapped)


def test_the_render_fps_is_real_time():
    assert gym.make("gpfd/CartPole-v0", render_mode="rgb_array").metadata["render_fps"] == 50
    assert gym.make("gpfd/Acrobot-v0", dt=0.1).metadata["render_fps"] == 10
    assert gym.make("gpfd/Swimmer-v0").metadata["render_fps"] == 10


def test_other_modes_are_refused_naming_rgb_array():
    with pytest.raises(ValueError, match="rgb_array"):
        GpfdEnv("cartpole", render_mode="human")
    with pytest.raises(ValueError, match="rgb_array"):
        gym.make_vec("gpfd/CartPole-v0", num_envs=2, render_mode="ansi")
    with pytest.warns(UserWarning, match="render_mode"):
        assert gym.make("gpfd/CartPole-v0").unwrapped.render() is None


def colour_at(frame: np.ndarray, x: float, y: float) -> tuple[int, int, int]:
    r, g, b = (int(v) for v in frame[int(y), int(x)])
    return r, g, b


def test_cartpole_pole_points_where_th_says():
    env = gpfd_env(gym.make("gpfd/CartPole-v0", render_mode="rgb_array"))
    env.reset(seed=0)
    scale = 600 / (2 * render.CARTPOLE_X_LIMIT)  # Pixels per metre.
    axle_x, axle_y = 300 + 1.0 * scale, 400 - 100 - 7.5  # The cart at x = 1 m.
    env.set_state([1.0, 0.0, 0.0, 0.0])
    upright = rgb(env)
    assert colour_at(upright, axle_x, axle_y - 0.8 * scale) == POLE
    env.set_state([1.0, 0.0, np.pi / 2, 0.0])  # Lying towards +x.
    lying = rgb(env)
    assert colour_at(lying, axle_x + 0.8 * scale, axle_y) == POLE
    assert colour_at(lying, axle_x, axle_y - 0.8 * scale) == (255, 255, 255)


def test_acrobot_links_hang_from_the_bar():
    env = gpfd_env(gym.make("gpfd/Acrobot-v0", render_mode="rgb_array"))
    env.reset(seed=0)
    scale = 500 / 4.4
    env.set_state([0.0, 0.0, 0.0, 0.0])  # Hanging straight down.
    down = rgb(env)
    assert colour_at(down, 250, 250 + 1.5 * scale) == LINK
    env.set_state([np.pi, 0.0, 0.0, 0.0])  # Straight up: the tip above the goal line.
    up = rgb(env)
    assert colour_at(up, 250, 250 - 1.5 * scale) == LINK
    assert colour_at(up, 250, 250 + 1.5 * scale) == (255, 255, 255)


def test_swimmer_frame_has_every_segment():
    env = gpfd_env(gym.make("gpfd/Swimmer-v0", segments=5, render_mode="rgb_array"))
    env.reset(seed=0)
    state = np.zeros(12)
    env.set_state(state)  # Straight along x, centred.
    straight = rgb(env)
    scale = 500 / 6.0
    segment_colours = {(30, 70, 160), (70, 130, 200)}
    for i in range(5):  # Segment i's centre, from the centre of mass at (250, 250).
        x = 250 + (i + 0.5 - 2.5) * scale
        assert colour_at(straight, x, 250 - 0.06 * scale) in segment_colours, i
    state[2::2] = np.pi / 2  # Straight along y.
    env.set_state(state)
    upright = rgb(env)
    assert colour_at(upright, 250 + 2 * scale, 250 - 0.06 * scale) == (255, 255, 255)
    assert colour_at(upright, 250 + 0.06 * scale, 250 - 2 * scale) in segment_colours


def test_tetris_frame_shows_the_board():
    env = gpfd_env(gym.make("gpfd/Tetris-v0", render_mode="rgb_array"))
    env.reset(seed=0)
    cell, margin = 24, 12

    def filled_cells(frame):
        rows, cols = 12, 8
        centres = frame[
            margin + cell // 2 : margin + rows * cell : cell,
            margin + cell // 2 : margin + cols * cell : cell,
        ]
        return (centres != (30, 30, 40)).any(axis=2)

    assert not filled_cells(rgb(env)).any()
    env.step(np.array([0, 0]))
    board = env._core.tetris_board(0)["cells"]
    assert board.sum() == 4
    assert np.array_equal(filled_cells(rgb(env)), board[::-1])  # Row 0 at the bottom.


@pytest.mark.parametrize("env_id", IDS)
def test_vector_render_gives_each_instance_as_a_single_environment_does(env_id):
    envs = gym.make_vec(env_id, num_envs=3, render_mode="rgb_array")
    assert envs.render_mode == "rgb_array"
    assert envs.metadata["render_modes"] == ["rgb_array"]
    envs.reset(seed=4)
    frames = envs.render()
    assert isinstance(frames, tuple) and len(frames) == 3
    for i, frame in enumerate(frames):
        single = gym.make(env_id, render_mode="rgb_array")
        single.reset(seed=4 + i)
        assert np.array_equal(frame, rgb(single))


def test_render_collection_and_rgb_array_list():
    env = gym.make("gpfd/CartPole-v0", render_mode="rgb_array_list")  # RenderCollection
    play(env, 6)
    frames = env.render()
    assert isinstance(frames, list) and len(frames) >= 6
    assert all(isinstance(f, np.ndarray) and f.shape == (400, 600, 3) for f in frames)
    wrapped = RenderCollection(gym.make("gpfd/Tetris-v0", render_mode="rgb_array"))
    play(wrapped, 3)
    collected = wrapped.render()
    assert (
        isinstance(collected, list) and len(collected) >= 4
    )  # The reset's frame and one per step.


def test_record_video_writes_a_video(tmp_path):
    pytest.importorskip("moviepy")
    env = RecordVideo(
        gym.make("gpfd/CartPole-v0", render_mode="rgb_array", max_steps=20),
        str(tmp_path / "videos"),
        episode_trigger=lambda episode: episode == 0,
        disable_logger=True,
    )
    env.reset(seed=0)
    for _ in range(20):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            break
    env.close()
    videos = list((tmp_path / "videos").glob("*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 0


def make_like_sb3():
    """What Stable-Baselines3's make_vec_env does for each instance (stable_baselines3/common/
    env_util.py): gym.make(env_id, render_mode="rgb_array"), in its own process under
    SubprocVecEnv. At module level, so that a spawned process imports this module, and with it
    gpfd, as it imports a user's script."""
    return gym.make("gpfd/CartPole-v0", render_mode="rgb_array")


@pytest.mark.parametrize("vector", ["sync", "spawned processes"])
def test_make_vec_env_call_path(vector):
    fns = [make_like_sb3, make_like_sb3]
    envs: gym.vector.VectorEnv = (
        SyncVectorEnv(fns) if vector == "sync" else AsyncVectorEnv(fns, context="spawn")
    )
    try:
        obs, _ = envs.reset(seed=0)
        assert np.shape(obs) == (2, 4)
        _, rewards, _, _, _ = envs.step(np.zeros((2, 1)))
        assert rewards.tolist() == [1.0, 1.0]
        frames = envs.render()
        assert isinstance(frames, tuple) and len(frames) == 2
        assert all(isinstance(f, np.ndarray) and f.shape == (400, 600, 3) for f in frames)
    finally:
        envs.close()


@pytest.mark.parametrize(
    "box",
    [(10.2, 20.7, 50.5, 33.5), (0, 99.5, 600, 100.5), (-5, -5, 3.49, 2.5), (590.5, 390, 700, 500)],
)
def test_rect_takes_the_pixels_its_polygon_takes(box):
    """Canvas.rect slices; Canvas.polygon tests pixel centres: the same pixels, clipped alike."""
    sliced, filled = render.Canvas(600, 400), render.Canvas(600, 400)
    x0, y0, x1, y1 = box
    sliced.rect(x0, y0, x1, y1, (1, 2, 3))
    filled.polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], (1, 2, 3))
    assert np.array_equal(sliced.pixels, filled.pixels)
    assert (sliced.pixels == (1, 2, 3)).all(axis=2).any()


@pytest.mark.parametrize("start", ["in process", "spawn"])
def test_stable_baselines3_make_vec_env(start):
    """SB3 itself, where it is installed (it needs torch, which the default test run leaves out;
    test_make_vec_env_call_path covers its calls without it)."""
    env_util = pytest.importorskip("stable_baselines3.common.env_util")
    from stable_baselines3.common.vec_env import SubprocVecEnv

    options: dict[str, Any] = {}
    env_id = "gpfd/CartPole-v0"
    if start == "spawn":
        options = {"vec_env_cls": SubprocVecEnv, "vec_env_kwargs": {"start_method": "spawn"}}
        env_id = "gpfd:" + env_id  # Gymnasium imports gpfd in the new process first.
    venv = env_util.make_vec_env(env_id, n_envs=2, seed=0, **options)
    try:
        venv.reset()
        obs, rewards, _, _ = venv.step(np.zeros((2, 1)))
        assert obs.shape == (2, 4) and rewards.tolist() == [1.0, 1.0]
        assert [f.shape for f in venv.get_images()] == [(400, 600, 3)] * 2
    finally:
        venv.close()
