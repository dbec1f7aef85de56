"""YOLOv8's training augmentations on numpy images, driven by an explicit numpy Generator.

Images are HxWx3 uint8 RGB. Boxes are float arrays [N, 5]: class, x1, y1, x2, y2 in pixel-edge
coordinates (pixel u spans [u, u + 1)), as the C++ letterbox (src/detection/letterbox.h) uses them.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

LETTERBOX_GREY = 114  # YOLOv8's padding value, also the C++ runtime's


@dataclass
class AugmentOptions:
    """Defaults are YOLOv8's hyper-parameters (ultralytics default.yaml) where it has one."""

    mosaic: bool = True  # 4-image mosaic (turned off for the last close_mosaic epochs by the trainer)
    scale: float = 0.5  # random affine zoom factor drawn from [1 - scale, 1 + scale]
    translate: float = 0.1  # random shift, a fraction of the output size
    hsv_h: float = 0.015  # hue gain (fraction of the hue circle)
    hsv_s: float = 0.7  # saturation gain
    hsv_v: float = 0.4  # value gain
    flip_lr: float = 0.5  # probability of a horizontal flip


@dataclass(frozen=True)
class Letterbox:
    """How an image of image_size (w, h) sits in an input of input_size (W, H); same rounding as C++."""

    image_size: tuple[int, int]
    input_size: tuple[int, int]
    scaled: tuple[int, int]
    pad_left: int
    pad_top: int

    @property
    def scale_x(self) -> float:
        return self.scaled[0] / self.image_size[0]

    @property
    def scale_y(self) -> float:
        return self.scaled[1] / self.image_size[1]


def fit_letterbox(image_size: tuple[int, int], input_size: tuple[int, int]) -> Letterbox:
    """The scale min(input / image), scaled size rounded half away from zero, padding split evenly."""
    (w, h), (in_w, in_h) = image_size, input_size
    scale = min(in_w / w, in_h / h)
    scaled_w = int(min(max(np.floor(w * scale + 0.5), 1), in_w))
    scaled_h = int(min(max(np.floor(h * scale + 0.5), 1), in_h))
    return Letterbox(image_size, input_size, (scaled_w, scaled_h), (in_w - scaled_w) // 2, (in_h - scaled_h) // 2)


def resize_to(image: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    if (image.shape[1], image.shape[0]) == tuple(size):
        return image
    return cv2.resize(image, size, interpolation=cv2.INTER_LINEAR)


def apply_letterbox(image: np.ndarray, box: Letterbox) -> np.ndarray:
    resized = resize_to(image, box.scaled)
    canvas = np.full((box.input_size[1], box.input_size[0], 3), LETTERBOX_GREY, dtype=np.uint8)
    canvas[box.pad_top : box.pad_top + box.scaled[1], box.pad_left : box.pad_left + box.scaled[0]] = resized
    return canvas


def letterbox_boxes(boxes: np.ndarray, box: Letterbox) -> np.ndarray:
    out = boxes.astype(np.float64, copy=True)
    out[:, [1, 3]] = out[:, [1, 3]] * box.scale_x + box.pad_left
    out[:, [2, 4]] = out[:, [2, 4]] * box.scale_y + box.pad_top
    return out


def mosaic4(
    images: list[np.ndarray], boxes: list[np.ndarray], input_size: tuple[int, int], rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray]:
    """YOLOv8's 4-image mosaic on a 2W x 2H grey canvas around a random centre in [W/2, 3W/2] x [H/2, 3H/2].

    Each image (already resized to fit W x H) is placed in one quadrant touching the centre; the
    random affine that follows crops the canvas back to W x H.
    """
    in_w, in_h = input_size
    canvas_w, canvas_h = 2 * in_w, 2 * in_h
    xc = int(rng.uniform(in_w / 2, 3 * in_w / 2))
    yc = int(rng.uniform(in_h / 2, 3 * in_h / 2))
    canvas = np.full((canvas_h, canvas_w, 3), LETTERBOX_GREY, dtype=np.uint8)
    placed = []
    for quadrant, (image, labels) in enumerate(zip(images, boxes)):
        h, w = image.shape[:2]
        if quadrant == 0:  # top left: the image's bottom-right corner at the centre
            x1a, y1a, x2a, y2a = max(xc - w, 0), max(yc - h, 0), xc, yc
            x1b, y1b = w - (x2a - x1a), h - (y2a - y1a)
        elif quadrant == 1:  # top right
            x1a, y1a, x2a, y2a = xc, max(yc - h, 0), min(xc + w, canvas_w), yc
            x1b, y1b = 0, h - (y2a - y1a)
        elif quadrant == 2:  # bottom left
            x1a, y1a, x2a, y2a = max(xc - w, 0), yc, xc, min(yc + h, canvas_h)
            x1b, y1b = w - (x2a - x1a), 0
        else:  # bottom right
            x1a, y1a, x2a, y2a = xc, yc, min(xc + w, canvas_w), min(yc + h, canvas_h)
            x1b, y1b = 0, 0
        canvas[y1a:y2a, x1a:x2a] = image[y1b : y1b + (y2a - y1a), x1b : x1b + (x2a - x1a)]
        shifted = labels.astype(np.float64, copy=True)
        shifted[:, [1, 3]] += x1a - x1b
        shifted[:, [2, 4]] += y1a - y1b
        # Only the part of a box inside the pasted window is visible.
        shifted[:, [1, 3]] = shifted[:, [1, 3]].clip(x1a, x2a)
        shifted[:, [2, 4]] = shifted[:, [2, 4]].clip(y1a, y2a)
        placed.append(shifted)
    return canvas, np.concatenate(placed, axis=0) if placed else np.zeros((0, 5))


def _keep_boxes(before: np.ndarray, after: np.ndarray, zoom: float) -> np.ndarray:
    """YOLOv8's box_candidates: > 2 px wide and high, > 10 % of the zoomed area left, aspect < 100."""
    w0, h0 = before[:, 3] - before[:, 1], before[:, 4] - before[:, 2]
    w1, h1 = after[:, 3] - after[:, 1], after[:, 4] - after[:, 2]
    aspect = np.maximum(w1 / (h1 + 1e-16), h1 / (w1 + 1e-16))
    return (w1 > 2) & (h1 > 2) & (w1 * h1 / (w0 * h0 * zoom * zoom + 1e-16) > 0.1) & (aspect < 100)


def random_affine(
    image: np.ndarray,
    boxes: np.ndarray,
    output_size: tuple[int, int],
    rng: np.random.Generator,
    *,
    scale: float,
    translate: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Zoom about the image centre by s ~ U(1 - scale, 1 + scale) and shift the centre to
    (0.5 + U(-translate, translate)) * output size; boxes that mostly leave the image are dropped."""
    out_w, out_h = output_size
    zoom = rng.uniform(1 - scale, 1 + scale)
    centre_x = rng.uniform(0.5 - translate, 0.5 + translate) * out_w
    centre_y = rng.uniform(0.5 - translate, 0.5 + translate) * out_h
    # Edge coordinates: p' = zoom * (p - image centre) + new centre.
    tx = centre_x - zoom * image.shape[1] / 2
    ty = centre_y - zoom * image.shape[0] / 2
    # cv2 maps pixel indices (centres at u + 0.5 in edge coordinates): shift by 0.5 * (zoom - 1).
    matrix = np.array([[zoom, 0.0, tx + 0.5 * (zoom - 1)], [0.0, zoom, ty + 0.5 * (zoom - 1)]])
    warped = cv2.warpAffine(
        image, matrix, (out_w, out_h), flags=cv2.INTER_LINEAR, borderValue=(LETTERBOX_GREY,) * 3
    )
    if len(boxes) == 0:
        return warped, boxes.reshape(0, 5)
    moved = boxes.astype(np.float64, copy=True)
    moved[:, [1, 3]] = moved[:, [1, 3]] * zoom + tx
    moved[:, [2, 4]] = moved[:, [2, 4]] * zoom + ty
    moved[:, [1, 3]] = moved[:, [1, 3]].clip(0, out_w)
    moved[:, [2, 4]] = moved[:, [2, 4]].clip(0, out_h)
    keep = _keep_boxes(boxes, moved, zoom)
    return warped, moved[keep]


def hsv_jitter(image: np.ndarray, rng: np.random.Generator, *, hue: float, saturation: float, value: float) -> np.ndarray:
    """Multiply hue, saturation and value by random gains 1 + U(-g, g) (YOLOv8's augment_hsv)."""
    if hue == 0 and saturation == 0 and value == 0:
        return image
    gains = rng.uniform(-1, 1, 3) * np.array([hue, saturation, value]) + 1
    h, s, v = cv2.split(cv2.cvtColor(image, cv2.COLOR_RGB2HSV))
    lut = np.arange(256, dtype=np.float64)
    lut_h = ((lut * gains[0]) % 180).astype(np.uint8)  # OpenCV's 8-bit hue runs over 0..179
    lut_s = np.clip(lut * gains[1], 0, 255).astype(np.uint8)
    lut_v = np.clip(lut * gains[2], 0, 255).astype(np.uint8)
    hsv = cv2.merge((cv2.LUT(h, lut_h), cv2.LUT(s, lut_s), cv2.LUT(v, lut_v)))
    return cv2.cvtColor(hsv, cv2.COLOR_HSV2RGB)


def flip_horizontal(image: np.ndarray, boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    width = image.shape[1]
    flipped = boxes.astype(np.float64, copy=True)
    flipped[:, 1], flipped[:, 3] = width - boxes[:, 3], width - boxes[:, 1]
    return np.ascontiguousarray(image[:, ::-1]), flipped
