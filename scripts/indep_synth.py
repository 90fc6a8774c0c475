#!/usr/bin/env python3
"""Synthetic sequences made independently of movseg's own generator (src/synth), to check that
what the methods learnt from synth and DAVIS holds elsewhere (docs/synth.md, "An independent
check"). Nothing of src/synth is shared: a textured plane (fractal 1/f noise, or the first frame
of a DAVIS sequence when --davis is given), seen by one of six camera motions; one or two
*small* camouflaged movers (irregular polygons of 15-33 px radius whose skin is cut from the same
texture) moving 1-3.5 px a frame over the plane; sensor noise sigma 2 and a gain drifting within
+-10 %. 40 frames of 320x240 each, OUT/<name>/frames/NNNNN.png and OUT/<name>/masks/NNNNN.png
(0/255), the layout `movseg bench OUT` reads.

  scripts/indep_synth.py OUT [--seeds 0-47] [--davis ../shared/data/davis2016] [--cameras dolly]

Seed s chooses the camera (s % 6: static pan zoom rotate shake mix) and the texture (fractal,
or with --davis every other six seeds a DAVIS frame); names are indep-<texture>-<camera>-<s>.
--cameras picks from another list: `dolly` is a 3-D scene instead of a plane — a camera moving
sideways (and a little forwards) 1.5 m above a ground plane, a wall 20 m away, two to four static
posts 4-10 m away that shift 1-4 px a frame more than the wall, and the movers at 6-15 m, hidden
where a post stands in front of them (render_dolly: every pixel's ray meets the nearest surface).
"""
import argparse
import math
import sys
from pathlib import Path

import cv2
import numpy as np

WIDTH, HEIGHT, FRAMES = 320, 240, 40
CAMERAS = ["static", "pan", "zoom", "rotate", "shake", "mix"]
# The dolly's pinhole camera (pixels) and its scene (metres; x right, y down, z forwards).
FOCAL, HORIZON = 300.0, HEIGHT / 2
EYE_HEIGHT, WALL_DEPTH, TEXELS_PER_METRE = 1.5, 20.0, 40.0
STEP = np.array([0.05, 0.0, 0.02])  # camera travel per frame


def fractal_texture(rng, size=1024):
    """Coloured 1/f noise with a random mixing of the channels."""
    f = np.fft.fftfreq(size)
    fx, fy = np.meshgrid(f, f)
    amplitude = 1 / np.maximum(np.hypot(fx, fy), 1 / size) ** 1.1
    channels = []
    for _ in range(3):
        phase = rng.uniform(0, 2 * np.pi, (size, size))
        t = np.real(np.fft.ifft2(amplitude * np.exp(1j * phase)))
        channels.append((t - t.mean()) / t.std())
    image = np.stack(channels, -1) @ (rng.normal(0, 1, (3, 3)) * 0.5 + np.eye(3)).T
    return np.clip(128 + 40 * image / image.std(), 0, 255).astype(np.uint8)


def davis_texture(rng, davis):
    sequences = sorted(p for p in Path(davis).iterdir() if (p / "frames").is_dir())
    first = sorted((sequences[rng.integers(len(sequences))] / "frames").iterdir())[0]
    return cv2.resize(cv2.imread(str(first)), (1024, 576), interpolation=cv2.INTER_AREA)


def camera(motion, t, texture_size):
    """The homography taking frame pixels to texture pixels at frame t."""
    tx = ty = angle = 0.0
    scale = 1.0
    if motion in ("pan", "mix"):
        tx, ty = 2.0 * t, 0.6 * t
    if motion in ("zoom", "mix"):
        scale = 1.0 - 0.005 * t
    if motion in ("rotate", "mix"):
        angle = 0.004 * t
    if motion == "shake":
        tx, ty = 3 * math.sin(1.7 * t) + 2 * math.sin(3.1 * t), 3 * math.cos(2.3 * t)
        angle = 0.006 * math.sin(1.3 * t)
    c, s = math.cos(angle) * scale, math.sin(angle) * scale
    centre = np.array([[1, 0, -WIDTH / 2], [0, 1, -HEIGHT / 2], [0, 0, 1]])
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    place = np.array([[1, 0, texture_size[1] / 2 + tx], [0, 1, texture_size[0] / 2 + ty],
                      [0, 0, 1]])
    return place @ turn @ centre


def polygon_mask(rng, radius):
    n = rng.integers(5, 9)
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    radii = radius * rng.uniform(0.6, 1.0, n)
    points = np.stack([radius + radii * np.cos(angles), radius + radii * np.sin(angles)], 1)
    mask = np.zeros((2 * radius + 1, 2 * radius + 1), np.uint8)
    cv2.fillPoly(mask, [points.astype(np.int32)], 255)
    return cv2.GaussianBlur(mask, (3, 3), 0)


def skin_from(rng, texture, radius):
    """A square of the texture, 2 radius + 1 on a side, from anywhere in it: camouflage."""
    top = rng.integers(0, texture.shape[0] - 2 * radius - 1)
    left = rng.integers(0, texture.shape[1] - 2 * radius - 1)
    return texture[top:top + 2 * radius + 1, left:left + 2 * radius + 1].copy()


def composite(frame, truth, alpha, colour):
    """A mover of coverage `alpha` and colour `colour` laid over the frame and its truth."""
    return frame * (1 - alpha[..., None]) + colour * alpha[..., None], np.maximum(truth, alpha)


def dolly_scene(rng, texture):
    """Posts and movers of a dolly sequence: (depth, x range, y range, skin) in metres and
    pixels; a mover also has its velocity in metres per frame and its polygon mask."""
    posts = []
    for _ in range(rng.integers(2, 5)):
        depth, width, tall = rng.uniform(4, 10), rng.uniform(0.2, 0.5), rng.uniform(1.5, 3.5)
        left = rng.uniform(-0.4, 0.5) * depth + 1  # in view for most of the travel
        posts.append((depth, (left, left + width), (EYE_HEIGHT - tall, EYE_HEIGHT)))
    movers = []
    for _ in range(rng.integers(1, 3)):
        radius = int(rng.integers(18, 40))
        depth = rng.uniform(6, 15)
        skin = skin_from(rng, texture, radius)
        heading = rng.uniform(0, 2 * np.pi)
        speed = rng.uniform(1, 3.5) * depth / FOCAL  # 1-3.5 px a frame at its depth
        velocity = speed * np.array([math.cos(heading), math.sin(heading)])
        centre = np.array([rng.uniform(-0.2, 0.6), rng.uniform(-0.12, 0.12)]) * depth
        movers.append((depth, centre, velocity, polygon_mask(rng, radius), skin))
    return posts, movers


def mirrored(coordinate, size):
    """Texture coordinates beyond the texture reflected back into it: tiles without seams."""
    period = 2 * (size - 1)
    return ((size - 1) - np.abs(np.mod(coordinate, period) - (size - 1))).astype(np.float32)


def render_dolly(texture, posts, movers, t):
    """Frame t of a dolly sequence and its movers' coverage: each pixel's ray meets the wall,
    the ground or a post, whichever is nearest; a mover is drawn where it is nearer still.
    Rendered at twice the size and averaged down, as a sensor integrates over its pixel."""
    eye = STEP * t
    x, y = np.meshgrid((np.arange(2 * WIDTH, dtype=np.float32) - 0.5) / 2,
                       (np.arange(2 * HEIGHT, dtype=np.float32) - 0.5) / 2)
    rx, ry = (x - WIDTH / 2) / FOCAL, (y - HORIZON) / FOCAL  # ray direction per unit depth
    with np.errstate(divide="ignore"):
        ground = np.where(ry > 0, EYE_HEIGHT / ry, np.inf)
    depth = np.minimum(ground, WALL_DEPTH - eye[2])
    on_ground = ground < WALL_DEPTH - eye[2]
    # texture coordinates: the wall by (x, y), the ground by (x, z), in world metres
    u = (eye[0] + rx * depth) * TEXELS_PER_METRE
    v = np.where(on_ground, (eye[2] + depth) * TEXELS_PER_METRE,
                 ry * depth * TEXELS_PER_METRE + texture.shape[0] / 2)
    for z, (left, right), (top, bottom) in posts:
        d = z - eye[2]
        wx, wy = eye[0] + rx * d, ry * d
        hit = (wx >= left) & (wx <= right) & (wy >= top) & (wy <= bottom) & (d < depth)
        depth = np.where(hit, d, depth)
        # a post's skin: texture rows up to 300, columns 300 texels on per metre of its depth
        u = np.where(hit, (wx - left) * TEXELS_PER_METRE + 300 * z, u)
        v = np.where(hit, wy * TEXELS_PER_METRE + 300, v)
    frame = cv2.remap(texture, mirrored(u, texture.shape[1]), mirrored(v, texture.shape[0]),
                      cv2.INTER_LINEAR).astype(np.float32)
    truth = np.zeros(x.shape, np.float32)
    for z, centre, velocity, mask, skin in movers:
        d = z - eye[2]
        at = centre + velocity * t
        radius = mask.shape[0] // 2
        corner = ((at[0] - eye[0]) * FOCAL / d + WIDTH / 2 - radius,
                  at[1] * FOCAL / d + HORIZON - radius)
        place = np.float32([[2, 0, 2 * corner[0] + 0.5], [0, 2, 2 * corner[1] + 0.5]])
        alpha = cv2.warpAffine(mask, place, x.shape[::-1]).astype(np.float32) / 255
        alpha *= d < depth
        colour = cv2.warpAffine(skin, place, x.shape[::-1]).astype(np.float32)
        frame, truth = composite(frame, truth, alpha, colour)
    return (cv2.resize(frame, (WIDTH, HEIGHT), interpolation=cv2.INTER_AREA),
            cv2.resize(truth, (WIDTH, HEIGHT), interpolation=cv2.INTER_AREA))


def render_plane(texture, movers, motion, t):
    """Frame t of a plane seen by `motion`, and its movers' coverage."""
    to_frame = np.linalg.inv(camera(motion, t, texture.shape))
    frame = cv2.warpPerspective(texture, to_frame, (WIDTH, HEIGHT),
                                borderMode=cv2.BORDER_REFLECT).astype(np.float32)
    truth = np.zeros((HEIGHT, WIDTH), np.float32)
    for mask, skin, start, velocity in movers:
        at = start + velocity * t
        warp = to_frame @ np.array([[1, 0, at[0]], [0, 1, at[1]], [0, 0, 1]])
        alpha = cv2.warpPerspective(mask, warp, (WIDTH, HEIGHT)).astype(np.float32) / 255
        colour = cv2.warpPerspective(skin, warp, (WIDTH, HEIGHT)).astype(np.float32)
        frame, truth = composite(frame, truth, alpha, colour)
    return frame, truth


def plane_movers(rng, texture, motion):
    movers = []
    for _ in range(rng.integers(1, 3)):
        radius = int(rng.integers(18, 40))
        skin = skin_from(rng, texture, radius)
        heading = rng.uniform(0, 2 * np.pi)
        velocity = rng.uniform(1, 3.5) * np.array([math.cos(heading), math.sin(heading)])
        start = camera(motion, 0, texture.shape) @ np.array(
            [rng.uniform(60, WIDTH - 60), rng.uniform(60, HEIGHT - 60), 1])
        movers.append((polygon_mask(rng, radius), skin, start[:2] - radius, velocity))
    return movers


def make_sequence(out, seed, davis, cameras):
    rng = np.random.default_rng(seed)
    motion = cameras[seed % len(cameras)]
    use_davis = davis is not None and (seed // 6) % 2 == 0
    texture = davis_texture(rng, davis) if use_davis else fractal_texture(rng)
    if motion == "dolly":
        posts, movers = dolly_scene(rng, texture)
        render = lambda t: render_dolly(texture, posts, movers, t)
    else:
        movers = plane_movers(rng, texture, motion)
        render = lambda t: render_plane(texture, movers, motion, t)
    name = f"indep-{'davis' if use_davis else 'fractal'}-{motion}-{seed}"
    (out / name / "frames").mkdir(parents=True, exist_ok=True)
    (out / name / "masks").mkdir(parents=True, exist_ok=True)
    for t in range(FRAMES):
        frame, truth = render(t)
        gain = 1 + 0.1 * math.sin(2 * math.pi * t / FRAMES + seed)
        frame = frame * gain + rng.normal(0, 2, frame.shape)
        cv2.imwrite(str(out / name / "frames" / f"{t:05d}.png"),
                    np.clip(frame, 0, 255).astype(np.uint8))
        cv2.imwrite(str(out / name / "masks" / f"{t:05d}.png"),
                    ((truth > 0.5) * 255).astype(np.uint8))
    return name


def seed_range(text):
    first, _, last = text.partition("-")
    return range(int(first), int(last or first) + 1)


def camera_list(text):
    cameras = text.split(",")
    unknown = [c for c in cameras if c not in CAMERAS + ["dolly"]]
    if unknown:
        raise argparse.ArgumentTypeError(f"no such camera: {', '.join(unknown)}")
    return cameras


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--seeds", type=seed_range, default=seed_range("0-47"))
    parser.add_argument("--davis", help="folder of DAVIS sequences whose first frames are textures")
    parser.add_argument("--cameras", type=camera_list, default=CAMERAS,
                        help=f"camera motions seed by seed (default {','.join(CAMERAS)}; "
                             "also: dolly)")
    args = parser.parse_args()
    if args.davis is not None and not Path(args.davis).is_dir():
        sys.exit(f"indep_synth.py: no such folder: {args.davis}")
    for seed in args.seeds:
        print(make_sequence(args.out, seed, args.davis, args.cameras))


if __name__ == "__main__":
    main()
