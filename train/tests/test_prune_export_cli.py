"""The prune and export subcommands end to end, and reference_boxes' decoding."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import torch

from randomized_model import random_detector
from semchain_train.__main__ import main
from semchain_train.checkpoint import load_checkpoint, save_checkpoint
from semchain_train.flops import measure
from semchain_train.reference_boxes import ReferenceOptions, detect_image, reference_boxes, split_flat_output
from synthetic_data import CLASS_NAMES, write_dataset


def _checkpoint(path: Path, seed: int = 0) -> Path:
    model = random_detector(False, False, classes=len(CLASS_NAMES), seed=seed)
    save_checkpoint(path, model, names=CLASS_NAMES, epoch=0, train_options={"input_size": [64, 64]})
    return path


def _data(root: Path) -> Path:
    rects = {"train": [[(0, (8, 8, 40, 40))], [(1, (10, 30, 50, 62))]], "val": [[(2, (20, 4, 60, 30))]]}
    return write_dataset(root, rects)


def test_prune_fine_tune_then_export(tmp_path: Path, capsys):
    weights = _checkpoint(tmp_path / "w.pt")
    run = tmp_path / "run"
    argv = ["prune", "--weights", str(weights), "--out", str(run), "--speedup", "2", "--data", str(_data(tmp_path / "d")),
            "--epochs", "1", "--batch", "2", "--workers", "0", "--threads", "1", "--no-progress", "--round-to", "8"]
    assert main(argv) == 0
    report = json.loads((run / "prune.json").read_text())
    assert report["input"] == "64x64" and report["achieved_speedup"] >= 2.0
    pruned = load_checkpoint(run / "pruned.pt").model
    assert measure(pruned, (64, 64)).gflops == pytest.approx(report["after"]["gflops"], abs=1e-3)
    widths = {g.name: g.size for g in load_checkpoint(weights).model.channel_groups()}
    for group in pruned.channel_groups():  # --round-to 8: pruned widths are multiples of 8
        assert group.size == widths[group.name] or group.size % 8 == 0
    assert sum(report["removed_channels"].values()) > 0
    assert (run / "best.pt").is_file() and report["fine_tuned"]["epochs"] == 1
    tuned = load_checkpoint(run / "best.pt")
    assert tuned.names == CLASS_NAMES
    assert measure(tuned.model, (64, 64)).parameters == report["after"]["parameters"]

    onnx_path = tmp_path / "m.onnx"
    assert main(["export", "--weights", str(run / "best.pt"), "--out", str(onnx_path), "--input", "64x64"]) == 0
    assert onnx_path.is_file()
    assert (tmp_path / "m.names").read_text().splitlines() == CLASS_NAMES
    assert "OpenCV DNN runs it" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv,message",
    [
        (["export", "--weights", "missing.pt", "--out", "m.onnx"], "missing.pt"),
        (["export", "--weights", "w.pt", "--out", "m.onnx", "--input", "100x100"], "multiples of 32"),
        (["prune", "--weights", "w.pt", "--out", "run", "--speedup", "0.5"], "at least 1.0"),
        (["prune", "--weights", "w.pt", "--out", "run", "--epochs", "2"], "--data is required"),
    ],
)
def test_bad_input_is_one_line_and_exit_1(tmp_path: Path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    _checkpoint(tmp_path / "w.pt")
    try:
        status = main(argv)
    except SystemExit as exit_:  # argparse's usage errors
        status = exit_.code
    assert status == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("semchain_train: error:") and message in err


class _StubNetwork:
    """One confident anchor with one-hot DFL bins, for a known-answer decoding test."""

    def __init__(self):
        self.path, self.names, self.input_size = Path("stub"), ["a", "b"], (64, 64)

    def __call__(self, image: np.ndarray) -> list[torch.Tensor]:
        maps = [torch.full((1, 66, 64 // s, 64 // s), -20.0) for s in (8, 16, 32)]
        j, i = 3, 2  # anchor centre (20, 28) at stride 8
        for side, bin_ in enumerate((1, 1, 2, 1)):  # l, t, r, b in strides
            maps[0][0, side * 16 + bin_, j, i] = 30.0
        maps[0][0, 64 + 1, j, i] = 3.0  # class "b"
        return maps


def test_reference_decoding_known_answer():
    # A 128x64 image in a 64x64 input: scale 0.5, padded 16 rows at the top.
    found = detect_image(_StubNetwork(), np.zeros((64, 128, 3), np.uint8), ReferenceOptions(input_size=(64, 64)))
    assert len(found) == 1 and found[0]["class"] == "b" and found[0]["class_id"] == 1
    assert found[0]["score"] == pytest.approx(1 / (1 + np.exp(-3.0)), rel=1e-6)
    # Input box (12, 20)-(36, 36) -> image ((x - 0) / 0.5, (y - 16) / 0.5).
    assert found[0]["box"] == pytest.approx([24.0, 8.0, 72.0, 40.0], abs=1e-4)


def test_split_flat_output_inverts_the_export_layout():
    flat = torch.arange(2 * 84, dtype=torch.float32).reshape(1, 2, 84)  # 64x64 input: 64 + 16 + 4 anchors
    maps = split_flat_output(flat, (64, 64))
    assert [tuple(m.shape) for m in maps] == [(1, 2, 8, 8), (1, 2, 4, 4), (1, 2, 2, 2)]
    assert maps[1][0, 1, 2, 3].item() == 84 + 64 + 2 * 4 + 3


def test_checkpoint_and_onnx_give_the_same_boxes(tmp_path: Path):
    model = random_detector(False, False, classes=len(CLASS_NAMES), seed=2)
    with torch.no_grad():
        for cls in model.head.cls:
            cls[-1].bias[2] = 2.0  # make class 2 fire so that NMS has work to do
    weights = tmp_path / "w.pt"
    save_checkpoint(weights, model, names=CLASS_NAMES, epoch=0)
    images = sorted((_data(tmp_path / "d").parent / "images" / "train").glob("*.png"))
    assert main(["export", "--weights", str(weights), "--out", str(tmp_path / "m.onnx"), "--input", "64x64"]) == 0
    options = ReferenceOptions(input_size=(64, 64))
    torch_boxes = reference_boxes(weights, images, options)
    opencv_boxes = reference_boxes(tmp_path / "m.onnx", images, options)
    assert torch_boxes["input"] == opencv_boxes["input"] == "64x64"
    count = 0
    for a, b in zip(torch_boxes["images"], opencv_boxes["images"]):
        assert [d["class_id"] for d in a["detections"]] == [d["class_id"] for d in b["detections"]]
        for da, db in zip(a["detections"], b["detections"]):
            assert da["box"] == pytest.approx(db["box"], abs=1e-3)
            count += 1
    assert count > 0


def test_reference_boxes_bad_input_is_one_line(tmp_path: Path, capsys):
    from semchain_train.reference_boxes import main as reference_main

    _checkpoint(tmp_path / "w.pt")
    assert reference_main(["--model", str(tmp_path / "w.pt"), "--images", str(tmp_path / "none"), "--out", str(tmp_path / "b.json")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "none: no such image or folder" in err
    (tmp_path / "empty").mkdir()
    assert reference_main(["--model", str(tmp_path / "missing.pt"), "--images", str(tmp_path / "empty"), "--out", str(tmp_path / "b.json")]) == 1
    assert capsys.readouterr().err.count("\n") == 1
