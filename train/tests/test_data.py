from pathlib import Path

import numpy as np
import pytest
import torch

from semchain_train.data.augment import (
    AugmentOptions,
    apply_letterbox,
    fit_letterbox,
    flip_horizontal,
    hsv_jitter,
    letterbox_boxes,
)
from semchain_train.data.dataset import (
    DataError,
    DetectionDataset,
    collate,
    label_path_of,
    load_data_yaml,
    parse_labels,
    split_images,
)
from synthetic_data import class_pixel_box, four_colour_dataset, write_dataset

NO_COLOUR = dict(hsv_h=0.0, hsv_s=0.0, hsv_v=0.0)


def test_labels_parse_and_blank_lines_are_skipped() -> None:
    rows = parse_labels("0 0.5 0.5 0.2 0.4\n\n3 0.1 0.9 0.2 0.2\r\n", "a.txt", 4)
    np.testing.assert_allclose(rows, [[0, 0.5, 0.5, 0.2, 0.4], [3, 0.1, 0.9, 0.2, 0.2]])


@pytest.mark.parametrize(
    "line, message",
    [
        ("4 0.5 0.5 0.1 0.1", "a.txt:2: class 4 out of range (nc 4)"),
        ("-1 0.5 0.5 0.1 0.1", "out of range"),
        ("x 0.5 0.5 0.1 0.1", "a.txt:2: class 'x' is not an integer"),
        ("1.0 0.5 0.5 0.1 0.1", "is not an integer"),
        ("1 0.5 0.5 0.1", "expected 'class cx cy w h'"),
        ("1 0.5 0.5 0.1 0.1 7", "got more fields"),
        ("1 nan 0.5 0.1 0.1", "'nan' is not a finite number"),
        ("1 0.5 abc 0.1 0.1", "'abc' is not a finite number"),
        ("1 1.5 0.5 0.1 0.1", "'1.5' lies outside [0, 1]"),
        ("1 0.95 0.5 0.2 0.1", "reaches outside the image"),
        ("1 0.5 0.5 0 0.1", "empty"),
    ],
)
def test_bad_label_lines_name_file_and_line(line: str, message: str) -> None:
    with pytest.raises(DataError, match=message.replace("[", r"\[").replace("]", r"\]").replace("(", r"\(").replace(")", r"\)")):
        parse_labels("0 0.5 0.5 0.1 0.1\n" + line + "\n", "a.txt", 4)


def test_data_yaml_paths_relative_to_path_and_file(tmp_path: Path) -> None:
    (tmp_path / "d" / "images" / "val").mkdir(parents=True)
    (tmp_path / "data.yaml").write_text("path: d\nval: images/val\nnames: [a, b]\n")
    spec = load_data_yaml(tmp_path / "data.yaml")
    assert spec.root == tmp_path / "d" and spec.splits == {"val": tmp_path / "d" / "images" / "val"}
    assert spec.names == ["a", "b"]
    (tmp_path / "e.yaml").write_text("val: /abs/images\nnames: {0: a, 1: b}\n")
    spec = load_data_yaml(tmp_path / "e.yaml")
    assert spec.root == tmp_path and spec.splits["val"] == Path("/abs/images")


@pytest.mark.parametrize(
    "text, message",
    [
        ("train: a\nnc: 3\nnames: [a, b]\n", "nc is 3 but names lists 2 classes"),
        ("nc: 2\nnames: [a, b]\n", "no split"),
        ("train: a\nnc: 2\n", "names: expected"),
        ("train: [a\n", "not valid YAML"),
        ("- 1\n- 2\n", "expected a mapping"),
    ],
)
def test_bad_data_yaml_is_one_clear_error(tmp_path: Path, text: str, message: str) -> None:
    (tmp_path / "data.yaml").write_text(text)
    with pytest.raises(DataError, match=message):
        load_data_yaml(tmp_path / "data.yaml")


def test_missing_split_folder_or_images_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(DataError, match="no such data.yaml"):
        load_data_yaml(tmp_path / "missing.yaml")
    (tmp_path / "images" / "train").mkdir(parents=True)
    (tmp_path / "data.yaml").write_text("train: images/train\nval: images/val\nnames: [a]\n")
    spec = load_data_yaml(tmp_path / "data.yaml")
    with pytest.raises(DataError, match="no images in the train split"):
        split_images(spec, "train")
    with pytest.raises(DataError, match="folder does not exist"):
        split_images(spec, "val")
    with pytest.raises(DataError, match="has no test split"):
        split_images(spec, "test")


def test_label_path_replaces_the_last_images_folder() -> None:
    assert label_path_of(Path("/x/images/d/images/train/a.png")) == Path("/x/images/d/labels/train/a.txt")


def test_letterbox_matches_the_cpp_rounding_and_moves_boxes_with_pixels() -> None:
    box = fit_letterbox((100, 50), (64, 64))
    assert box.scaled == (64, 32) and (box.pad_left, box.pad_top) == (0, 16)
    image = np.zeros((50, 100, 3), np.uint8)
    image[10:30, 20:70] = (255, 0, 0)
    boxes = np.array([[0, 20, 10, 70, 30]], float)
    moved = letterbox_boxes(boxes, box)
    np.testing.assert_allclose(moved[0, 1:], [12.8, 22.4, 44.8, 35.2])
    pixels = class_pixel_box(apply_letterbox(image, box), 0)
    np.testing.assert_allclose(pixels, moved[0, 1:], atol=1.0)


def test_flip_mirrors_boxes_exactly() -> None:
    image = np.zeros((20, 30, 3), np.uint8)
    image[2:5, 3:10] = (0, 255, 0)
    flipped, boxes = flip_horizontal(image, np.array([[1, 3, 2, 10, 5]], float))
    np.testing.assert_allclose(boxes, [[1, 20, 2, 27, 5]])
    assert class_pixel_box(flipped, 1) == (20.0, 2.0, 27.0, 5.0)


def test_hsv_jitter_changes_colours_reproducibly() -> None:
    image = np.random.default_rng(0).integers(0, 256, (16, 16, 3), dtype=np.uint8)
    a = hsv_jitter(image, np.random.default_rng(3), hue=0.015, saturation=0.7, value=0.4)
    b = hsv_jitter(image, np.random.default_rng(3), hue=0.015, saturation=0.7, value=0.4)
    assert np.array_equal(a, b) and not np.array_equal(a, image)
    assert np.array_equal(hsv_jitter(image, np.random.default_rng(3), hue=0, saturation=0, value=0), image)


@pytest.mark.parametrize("mosaic", [False, True])
def test_boxes_follow_the_pixels_through_mosaic_affine_and_flip(tmp_path: Path, mosaic: bool) -> None:
    data = four_colour_dataset(tmp_path, size=(80, 64), splits=("train",))
    options = AugmentOptions(mosaic=mosaic, **NO_COLOUR)
    dataset = DetectionDataset(load_data_yaml(data), "train", (64, 64), augment=options, seed=5)
    checked = 0
    for epoch in range(6):
        dataset.set_epoch(epoch)
        for index in range(len(dataset)):
            image, boxes = dataset[index]
            assert image.shape == (64, 64, 3) and image.dtype == np.uint8
            classes = list(boxes[:, 0].astype(int))
            assert len(set(classes)) == len(classes)  # distinct mosaic partners
            for row in boxes:
                pixels = class_pixel_box(image, int(row[0]))
                assert pixels is not None, f"class {int(row[0])} labelled but not visible"
                np.testing.assert_allclose(pixels, row[1:], atol=1.0)
                checked += 1
    assert checked >= 20


def test_validation_samples_are_plain_letterboxes(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path, size=(80, 64), splits=("val",))
    dataset = DetectionDataset(load_data_yaml(data), "val", (64, 64))
    image, boxes = dataset[1]
    assert boxes.shape == (1, 5)
    # 80x64 -> 64x51 (51.2 rounded), padded 6 px above.
    np.testing.assert_allclose(boxes[0, 1:], [26.0 * 0.8, 16 * 51 / 64 + 6, 70 * 0.8, 43 * 51 / 64 + 6], atol=1e-3)
    np.testing.assert_allclose(class_pixel_box(image, 1), boxes[0, 1:], atol=1.0)


def test_augmentation_is_reproducible_and_independent_of_workers(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path, splits=("train",))
    spec = load_data_yaml(data)

    def batches(seed: int, workers: int, epoch: int) -> list[tuple[torch.Tensor, torch.Tensor]]:
        dataset = DetectionDataset(spec, "train", (64, 64), augment=AugmentOptions(), seed=seed)
        dataset.set_epoch(epoch)
        loader = torch.utils.data.DataLoader(dataset, batch_size=2, num_workers=workers, collate_fn=collate)
        return list(loader)

    first = batches(1, 0, 0)
    for other in (batches(1, 0, 0), batches(1, 2, 0)):
        for (a_images, a_targets), (b_images, b_targets) in zip(first, other):
            assert torch.equal(a_images, b_images) and torch.equal(a_targets, b_targets)
    assert not torch.equal(first[0][0], batches(2, 0, 0)[0][0])
    assert not torch.equal(first[0][0], batches(1, 0, 1)[0][0])


def test_collate_shapes_and_batch_index() -> None:
    a = (np.full((8, 16, 3), 255, np.uint8), np.array([[1, 0, 0, 4, 4]], float))
    b = (np.zeros((8, 16, 3), np.uint8), np.array([[0, 1, 1, 2, 2], [2, 3, 3, 5, 5]], float))
    images, targets = collate([a, b])
    assert images.shape == (2, 3, 8, 16) and images.dtype == torch.float32
    assert images[0].min() == 1.0 and images[1].max() == 0.0
    assert targets.tolist() == [[0, 1, 0, 0, 4, 4], [1, 0, 1, 1, 2, 2], [1, 2, 3, 3, 5, 5]]


def test_bad_label_in_a_split_fails_at_construction(tmp_path: Path) -> None:
    data = write_dataset(tmp_path, {"train": [[(0, (1, 1, 9, 9))]]})
    (tmp_path / "labels" / "train" / "000.txt").write_text("0 0.5 0.5 0.2 0.2\n9 0.5 0.5 0.1 0.1\n")
    with pytest.raises(DataError, match=r"labels/train/000.txt:2: class 9 out of range \(nc 4\)"):
        DetectionDataset(load_data_yaml(data), "train", (64, 64))
