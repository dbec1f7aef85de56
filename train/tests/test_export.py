"""Raw-head ONNX export: OpenCV 4.6's DNN gives PyTorch's output for every neck combination and
for a pruned model, in the anchor order of src/detection/yolo_head.h."""

from __future__ import annotations

from pathlib import Path

import onnx
import pytest
import torch

from randomized_model import COMBINATION_IDS, COMBINATIONS, random_detector
from semchain_train.export import OPSET, RawHeadExport, check_with_opencv, export_onnx, parse_size
from semchain_train.lamp import PruneOptions, prune

SIZE = (128, 96)  # width, height
ANCHORS = 16 * 12 + 8 * 6 + 4 * 3


@pytest.mark.parametrize("gd,asf", COMBINATIONS, ids=COMBINATION_IDS)
def test_opencv_runs_the_export_as_pytorch(tmp_path: Path, gd: bool, asf: bool):
    model = random_detector(gd, asf, seed=7)
    path = tmp_path / "m.onnx"
    export_onnx(model, path, SIZE)
    graph = onnx.load(str(path))
    assert graph.opset_import[0].version == OPSET
    assert [d.dim_value for d in graph.graph.input[0].type.tensor_type.shape.dim] == [1, 3, 96, 128]
    assert [d.dim_value for d in graph.graph.output[0].type.tensor_type.shape.dim] == [1, 74, ANCHORS]
    assert check_with_opencv(model, path, SIZE) < 1e-3


def test_pruned_gd_asf_model_exports_and_runs_in_opencv(tmp_path: Path):
    model = random_detector(True, True, seed=8)
    result = prune(model, PruneOptions(speedup=2.0, input_size=(64, 64)))
    assert result.speedup >= 2.0
    path = tmp_path / "pruned.onnx"
    export_onnx(model, path, SIZE)
    assert check_with_opencv(model, path, SIZE, seed=1) < 1e-3


def test_anchor_order_is_row_major_per_stride():
    model = random_detector(False, False, seed=9)
    x = torch.rand(1, 3, 96, 128)
    with torch.no_grad():
        maps = model(x)
        flat = RawHeadExport(model)(x)
    assert flat.shape == (1, 74, ANCHORS)
    offset = 0
    for m in maps:
        h, w = m.shape[2:]
        for j, i in ((0, 0), (1, 2), (h - 1, w - 1)):
            assert torch.equal(flat[0, :, offset + j * w + i], m[0, :, j, i])
        offset += h * w


def test_bad_input_size_is_refused():
    assert parse_size("320x256") == (320, 256)
    for text in ("320", "320x250", "0x256", "axb"):
        with pytest.raises(ValueError, match="--input"):
            parse_size(text)


def test_an_export_opencv_runs_differently_replaces_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    import argparse

    import semchain_train.export as export

    model = random_detector(False, False, seed=10)
    monkeypatch.setattr(export, "load_model_and_names", lambda weights: (model, ["a", "b", "c", "d", "e", "f", "g", "h", "i", "j"]))
    out = tmp_path / "m.onnx"
    out.write_bytes(b"the previous export")
    args = argparse.Namespace(weights=tmp_path / "w.pt", out=out, input=SIZE, no_check=False, half=False)
    monkeypatch.setattr(export, "check_with_opencv", lambda *a, **k: 0.01)
    with pytest.raises(ValueError, match="differs from PyTorch by 0.01 of the largest output"):
        export.run(args)
    assert out.read_bytes() == b"the previous export"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.onnx"]
    monkeypatch.setattr(export, "check_with_opencv", lambda *a, **k: 1e-5)
    assert export.run(args) == 0
    assert onnx.load(str(out)).opset_import[0].version == OPSET
    assert (tmp_path / "m.names").read_text().splitlines()[0] == "a"
