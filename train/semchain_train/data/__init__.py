"""Data sets (data.yaml, images, YOLO labels) and YOLOv8's augmentations."""

from semchain_train.data.augment import AugmentOptions
from semchain_train.data.dataset import DataError, DatasetSpec, DetectionDataset, collate, load_data_yaml

__all__ = ["AugmentOptions", "DataError", "DatasetSpec", "DetectionDataset", "collate", "load_data_yaml"]
