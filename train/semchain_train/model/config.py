"""Model configuration: YOLOv8 scale and the seed-000 neck switches (GD neck, ASF)."""

from __future__ import annotations

import math
from dataclasses import dataclass

# (depth multiple, width multiple, max channels) of ultralytics' yolov8.yaml scales.
SCALES: dict[str, tuple[float, float, int]] = {
    "n": (0.33, 0.25, 1024),
    "s": (0.33, 0.50, 1024),
}


@dataclass
class ModelConfig:
    """What build_detector builds.

    scale    "n" or "s" (YOLOv8's depth 0.33, width 0.25 / 0.50, at most 1024 channels)
    classes  number of object classes (seed 000: 10)
    gd_neck  Gold-YOLO's gather-and-distribute neck in place of the PAN (seed 000 §2.1)
    asf      ASF-YOLO's attentional scale-sequence fusion (SSFF + TFE + CPAM giving N3)
    """

    scale: str = "n"
    classes: int = 10
    gd_neck: bool = False
    asf: bool = False

    def validate(self) -> None:
        if self.scale not in SCALES:
            raise ValueError(f"model scale {self.scale!r}: expected one of {', '.join(SCALES)}")
        if self.classes < 1:
            raise ValueError(f"model classes {self.classes}: expected at least 1")

    def channels(self, base: int) -> int:
        """YOLOv8's width scaling of a yolov8.yaml channel count: min(base, max) * width, to a multiple of 8."""
        _, width, max_channels = SCALES[self.scale]
        return int(math.ceil(min(base, max_channels) * width / 8) * 8)

    def depth(self, base: int) -> int:
        """YOLOv8's depth scaling of a repeat count (at least 1)."""
        depth, _, _ = SCALES[self.scale]
        return max(round(base * depth), 1)
