"""YOLO-format data sets as ultralytics lays them out (and src/detection/yolo_dataset.cc reads them).

data.yaml: `path` (the root; absent or relative: the yaml's folder, or relative to it), the splits
`train`, `val`, `test` (image folders relative to the root), `nc` and `names`. Labels lie beside the
images with the last `images` folder replaced by `labels` and the extension `.txt`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import cv2
import numpy as np
import torch
import yaml

from semchain_train.data.augment import (
    AugmentOptions,
    apply_letterbox,
    fit_letterbox,
    flip_horizontal,
    hsv_jitter,
    letterbox_boxes,
    mosaic4,
    random_affine,
    resize_to,
)

IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg", ".bmp")
SPLITS = ("train", "val", "test")


class DataError(ValueError):
    """Bad input data; the message names the file (and line) and what is wrong."""


@dataclass
class DatasetSpec:
    yaml_path: Path
    root: Path
    names: list[str]
    splits: dict[str, Path] = field(default_factory=dict)


def load_data_yaml(path: Path | str) -> DatasetSpec:
    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such data.yaml")
    try:
        content = yaml.safe_load(path.read_text())
    except (yaml.YAMLError, UnicodeDecodeError) as error:
        raise DataError(f"{path}: not valid YAML ({str(error).splitlines()[0]})") from None
    if not isinstance(content, dict):
        raise DataError(f"{path}: expected a mapping with path, train, val, test, nc and names")
    root = path.parent
    if content.get("path") is not None:
        given = Path(str(content["path"]))
        root = given if given.is_absolute() else path.parent / given
    names = content.get("names")
    if isinstance(names, dict):  # ultralytics also allows {0: door, 1: cabinet, ...}
        if sorted(names) != list(range(len(names))):
            raise DataError(f"{path}: names as a mapping must have the keys 0..{len(names) - 1}")
        names = [names[i] for i in range(len(names))]
    if not isinstance(names, list) or not names or not all(isinstance(n, (str, int)) for n in names):
        raise DataError(f"{path}: names: expected a non-empty list of class names")
    names = [str(n) for n in names]
    if "nc" in content and content["nc"] != len(names):
        raise DataError(f"{path}: nc is {content['nc']} but names lists {len(names)} classes")
    splits: dict[str, Path] = {}
    for split in SPLITS:
        if content.get(split) is None:
            continue
        if not isinstance(content[split], str):
            raise DataError(f"{path}: {split}: expected one image folder")
        folder = Path(content[split])
        splits[split] = folder if folder.is_absolute() else root / folder
    if not splits:
        raise DataError(f"{path}: no split (train, val or test) is given")
    return DatasetSpec(yaml_path=path, root=root, names=names, splits=splits)


def split_images(spec: DatasetSpec, split: str) -> list[Path]:
    """The sorted images of a split; an error when the split is absent, missing or empty."""
    if split not in SPLITS:
        raise DataError(f"split '{split}': expected train, val or test")
    if split not in spec.splits:
        raise DataError(f"{spec.yaml_path}: the data set has no {split} split")
    folder = spec.splits[split]
    if not folder.is_dir():
        raise DataError(f"{folder}: the {split} split's folder does not exist")
    images = sorted(p for p in folder.iterdir() if p.suffix.lower() in IMAGE_EXTENSIONS)
    if not images:
        raise DataError(f"{folder}: no images in the {split} split")
    return images


def label_path_of(image: Path) -> Path:
    parts = list(image.parts)
    for i in range(len(parts) - 1, -1, -1):
        if parts[i] == "images":
            parts[i] = "labels"
            break
    return Path(*parts).with_suffix(".txt")


def parse_labels(text: str, source: str, classes: int) -> np.ndarray:
    """Lines `class cx cy w h` (normalized) -> [N, 5] float64; refuses what the C++ reader refuses."""
    rows = []
    slack = 1e-6  # rounding of the printed numbers
    for number, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields:
            continue
        where = f"{source}:{number}: "
        try:
            class_id = int(fields[0])
        except ValueError:
            raise DataError(f"{where}class '{fields[0]}' is not an integer") from None
        if not 0 <= class_id < classes:
            raise DataError(f"{where}class {fields[0]} out of range (nc {classes})")
        if len(fields) < 5:
            raise DataError(f"{where}expected 'class cx cy w h'")
        if len(fields) > 5:
            raise DataError(f"{where}expected 'class cx cy w h', got more fields")
        values = []
        for item in fields[1:]:
            try:
                value = float(item)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise DataError(f"{where}'{item}' is not a finite number")
            if not 0.0 <= value <= 1.0:
                raise DataError(f"{where}'{item}' lies outside [0, 1]")
            values.append(value)
        cx, cy, w, h = values
        if w <= 0 or h <= 0 or cx - w / 2 < -slack or cx + w / 2 > 1 + slack or cy - h / 2 < -slack or cy + h / 2 > 1 + slack:
            raise DataError(f"{where}the box is empty or reaches outside the image")
        rows.append([class_id, cx, cy, w, h])
    return np.array(rows, dtype=np.float64).reshape(-1, 5)


def read_labels(path: Path, classes: int) -> np.ndarray:
    """An absent label file is an image without objects (ultralytics)."""
    if not path.exists():
        return np.zeros((0, 5))
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as error:
        raise DataError(f"{path}: cannot read the label file ({error})") from None
    return parse_labels(text, str(path), classes)


def to_pixel_boxes(labels: np.ndarray, width: int, height: int) -> np.ndarray:
    """[N, 5] normalized class cx cy w h -> class x1 y1 x2 y2 in pixels."""
    out = np.empty_like(labels, dtype=np.float64)
    out[:, 0] = labels[:, 0]
    out[:, 1] = (labels[:, 1] - labels[:, 3] / 2) * width
    out[:, 2] = (labels[:, 2] - labels[:, 4] / 2) * height
    out[:, 3] = (labels[:, 1] + labels[:, 3] / 2) * width
    out[:, 4] = (labels[:, 2] + labels[:, 4] / 2) * height
    return out


def read_rgb(path: Path) -> np.ndarray:
    bgr = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if bgr is None:
        raise DataError(f"{path}: cannot read the image")
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def sample_rng(seed: int, epoch: int, index: int) -> np.random.Generator:
    """The generator of one training sample (stream 0 of the run's seed)."""
    return np.random.default_rng((seed, 0, epoch, index))


def epoch_order(seed: int, epoch: int, size: int) -> list[int]:
    """The shuffled sample order of an epoch (stream 1 of the run's seed)."""
    return [int(i) for i in np.random.default_rng((seed, 1, epoch)).permutation(size)]


class DetectionDataset(torch.utils.data.Dataset):
    """One split. Labels are read (and checked) up front, images on demand.

    Augmentation draws from sample_rng(seed, epoch, index): a sample depends on nothing else, so runs
    are reproducible for any number of DataLoader workers and resume exactly.
    """

    def __init__(
        self,
        spec: DatasetSpec,
        split: str,
        input_size: tuple[int, int],
        *,
        augment: AugmentOptions | None = None,
        seed: int = 0,
    ) -> None:
        self.spec = spec
        self.split = split
        self.input_size = tuple(input_size)
        self.augment = augment
        self.seed = seed
        self.epoch = 0
        self.mosaic = augment is not None and augment.mosaic
        self.images = split_images(spec, split)
        self.labels = [read_labels(label_path_of(p), len(spec.names)) for p in self.images]

    def set_epoch(self, epoch: int, *, mosaic: bool | None = None) -> None:
        self.epoch = epoch
        if mosaic is not None:
            self.mosaic = mosaic and self.augment is not None and self.augment.mosaic

    def __len__(self) -> int:
        return len(self.images)

    def load_resized(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """The image resized to fit the input (aspect kept, no padding) and its pixel boxes."""
        image = read_rgb(self.images[index])
        h, w = image.shape[:2]
        fit = fit_letterbox((w, h), self.input_size)
        boxes = to_pixel_boxes(self.labels[index], w, h)
        boxes[:, [1, 3]] *= fit.scale_x
        boxes[:, [2, 4]] *= fit.scale_y
        return resize_to(image, fit.scaled), boxes

    def load_letterboxed(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        image = read_rgb(self.images[index])
        h, w = image.shape[:2]
        fit = fit_letterbox((w, h), self.input_size)
        return apply_letterbox(image, fit), letterbox_boxes(to_pixel_boxes(self.labels[index], w, h), fit)

    def __getitem__(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """(HxWx3 uint8 RGB of input_size, [N, 5] class x1 y1 x2 y2 in input pixels)."""
        if self.augment is None:
            return self.load_letterboxed(index)
        options = self.augment
        rng = sample_rng(self.seed, self.epoch, index)
        if self.mosaic:
            others = [i for i in range(len(self)) if i != index]
            # Distinct partners when there are enough images, so an object appears once per mosaic.
            picks = rng.choice(others, size=3, replace=len(others) < 3) if others else [index] * 3
            parts = [self.load_resized(i) for i in [index, *picks]]
            image, boxes = mosaic4([p[0] for p in parts], [p[1] for p in parts], self.input_size, rng)
        else:
            image, boxes = self.load_letterboxed(index)
        image, boxes = random_affine(
            image, boxes, self.input_size, rng, scale=options.scale, translate=options.translate
        )
        image = hsv_jitter(image, rng, hue=options.hsv_h, saturation=options.hsv_s, value=options.hsv_v)
        if rng.uniform() < options.flip_lr:
            image, boxes = flip_horizontal(image, boxes)
        return image, boxes


def collate(batch: list[tuple[np.ndarray, np.ndarray]]) -> tuple[torch.Tensor, torch.Tensor]:
    """-> images [B, 3, H, W] float 0..1 RGB, targets [M, 6] (batch index, class, x1, y1, x2, y2)."""
    images = torch.from_numpy(np.stack([image for image, _ in batch])).permute(0, 3, 1, 2).float().div_(255.0)
    targets = []
    for i, (_, boxes) in enumerate(batch):
        rows = np.zeros((len(boxes), 6), dtype=np.float32)
        rows[:, 0] = i
        rows[:, 1:] = boxes
        targets.append(rows)
    return images.contiguous(), torch.from_numpy(np.concatenate(targets, axis=0)).reshape(-1, 6)
