"""Training goes on from an exported model: the ONNX loaded back computes what the export computes,
in eval mode exactly and in train mode (batch statistics) nearly; other architectures are refused."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import onnx
import pytest
import torch
from randomized_model import random_detector

from semchain_train.export import check_with_opencv, export_onnx
from semchain_train.model.blocks import Conv
from semchain_train.model.config import ModelConfig
from semchain_train.onnx_import import OnnxImportError, float32_model, load_detector_from_onnx

SIZE = (96, 64)  # width, height: small, a multiple of 32


def _flat(maps: list[torch.Tensor]) -> torch.Tensor:
    return torch.cat([m.flatten(2) for m in maps], 2)


def _images(count: int, seed: int) -> torch.Tensor:
    # Smooth random images (not white noise), so that activations resemble those of real frames.
    generator = torch.Generator().manual_seed(seed)
    coarse = torch.rand(count, 3, SIZE[1] // 8, SIZE[0] // 8, generator=generator)
    return torch.nn.functional.interpolate(coarse, size=(SIZE[1], SIZE[0]), mode="bilinear", align_corners=False)


@pytest.fixture(scope="module")
def exported(tmp_path_factory: pytest.TempPathFactory) -> tuple[torch.nn.Module, Path]:
    model = random_detector(False, False, seed=3)
    path = tmp_path_factory.mktemp("onnx") / "m.onnx"
    export_onnx(model, path, SIZE)
    return model, path


def _signal(maps: torch.Tensor) -> float:
    return float(maps.std())


def test_eval_mode_computes_the_export(exported):
    original, path = exported
    loaded = load_detector_from_onnx(path, ModelConfig(scale="n", classes=10), _images(16, 1)).eval()
    x = _images(2, 2)
    with torch.no_grad():
        expected, got = _flat(original(x)), _flat(loaded(x))
    assert float((got - expected).abs().max()) < 1e-4 * _signal(expected)


def _block_outputs(model: torch.nn.Module, x: torch.Tensor, train: bool) -> list[torch.Tensor]:
    outputs: list[torch.Tensor] = []
    model = copy.deepcopy(model)  # train mode moves the running statistics
    hooks = [m.register_forward_hook(lambda m, i, o: outputs.append(o)) for m in model.modules() if isinstance(m, Conv)]
    with torch.no_grad():
        model.train(train)(x)
    for hook in hooks:
        hook.remove()
    return outputs


def _worst_block_error(model: torch.nn.Module, x: torch.Tensor) -> float:
    """Over every Conv block: max |train-mode output - eval-mode output| / the block's output std."""
    train, evaluation = _block_outputs(model, x, True), _block_outputs(model, x, False)
    return max(float((t - e).abs().max()) / max(float(e.std()), 1e-6) for t, e in zip(train, evaluation))


def test_train_mode_computes_what_eval_mode_computes(exported):
    _, path = exported
    calibration = _images(16, 1)
    loaded = load_detector_from_onnx(path, ModelConfig(scale="n", classes=10), calibration)
    # Batch statistics of the calibration images are the running statistics: every block agrees.
    assert _worst_block_error(loaded, calibration) < 1e-3
    # Other images of the same kind: close, so fine-tuning starts from the exported function.
    assert _worst_block_error(loaded, _images(16, 7)) < 0.5
    # Statistics that are not the data's (one black image) renormalise the blocks in train mode.
    naive = load_detector_from_onnx(path, ModelConfig(scale="n", classes=10), torch.zeros(1, 3, SIZE[1], SIZE[0]))
    assert _worst_block_error(naive, calibration) > 2.0


def test_another_architecture_is_refused(exported):
    _, path = exported
    with pytest.raises(OnnxImportError, match="another architecture"):
        load_detector_from_onnx(path, ModelConfig(scale="s", classes=10), _images(2, 1))
    with pytest.raises(OnnxImportError, match="another architecture"):
        load_detector_from_onnx(path, ModelConfig(scale="n", classes=10, gd_neck=True), _images(2, 1))


def test_not_an_onnx_file_is_one_error(tmp_path: Path):
    bad = tmp_path / "bad.onnx"
    bad.write_bytes(b"not a protobuf at all \x00\xff")
    with pytest.raises(OnnxImportError, match="bad.onnx"):
        load_detector_from_onnx(bad, ModelConfig(), _images(1, 1))


def test_half_export_is_half_the_size_and_runs_as_float(tmp_path: Path, exported):
    original, full_path = exported
    half_path = tmp_path / "half.onnx"
    export_onnx(original, half_path, SIZE, half=True)
    assert half_path.stat().st_size < 0.6 * full_path.stat().st_size
    half = onnx.load(str(half_path))
    assert any(init.data_type == onnx.TensorProto.FLOAT16 for init in half.graph.initializer)
    restored = float32_model(half)
    assert all(init.data_type != onnx.TensorProto.FLOAT16 for init in restored.graph.initializer)
    assert not any(node.op_type == "Cast" for node in restored.graph.node)
    # OpenCV runs the restored graph as PyTorch runs the float model, to the weights' rounding.
    assert check_with_opencv(original, half_path, SIZE) < 1e-2
    loaded = load_detector_from_onnx(half_path, ModelConfig(scale="n", classes=10), _images(8, 1)).eval()
    x = _images(1, 5)
    with torch.no_grad():
        expected = _flat(original(x)).numpy()
        got = _flat(loaded(x)).numpy()
    assert np.abs(got - expected).max() < 1e-2 * np.abs(expected).max()
