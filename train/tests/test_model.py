"""The detector's architecture against ultralytics' published YOLOv8 numbers and its contract."""

from __future__ import annotations

import io
import math

import pytest
import torch
from torch import nn

from randomized_model import COMBINATION_IDS, COMBINATIONS, randomize_batch_norms
from semchain_train.flops import count_parameters, measure
from semchain_train.model.asf import ScaleSequenceConv3d
from semchain_train.model.config import ModelConfig
from semchain_train.model.detector import build_detector

# ultralytics' model summaries (80 classes): YOLOv8n 3,157,200 parameters, 8.7 GFLOPs at 640;
# YOLOv8s 11,166,560 parameters, 28.6 GFLOPs. Both include the DFL's fixed 16-weight conv, which
# this package leaves to the decoders (16 fewer parameters).
ULTRALYTICS_V8N_PARAMS = 3_157_200
ULTRALYTICS_V8S_PARAMS = 11_166_560
DFL_WEIGHTS = 16


def test_yolov8n_and_s_match_ultralytics_parameter_counts():
    assert count_parameters(build_detector(ModelConfig("n", 80))) == ULTRALYTICS_V8N_PARAMS - DFL_WEIGHTS
    assert count_parameters(build_detector(ModelConfig("s", 80))) == ULTRALYTICS_V8S_PARAMS - DFL_WEIGHTS


def test_yolov8n_ten_classes_is_about_three_million_parameters_and_8_gflops_at_640():
    model = build_detector(ModelConfig("n", 10))
    cost = measure(model, (640, 640))
    assert abs(cost.parameters - 3.0e6) < 0.05e6
    assert cost.gflops == pytest.approx(8.1, abs=0.1)  # the 80-class head makes ultralytics' 8.7


@pytest.mark.parametrize("gd,asf", COMBINATIONS, ids=COMBINATION_IDS)
def test_output_contract_and_backward(gd, asf):
    model = build_detector(ModelConfig("n", 3, gd, asf))
    assert model.strides == (8, 16, 32) and model.reg_max == 16 and model.classes == 3
    x = torch.rand(2, 3, 96, 128)
    outputs = model(x)
    assert [tuple(o.shape) for o in outputs] == [(2, 67, 12, 16), (2, 67, 6, 8), (2, 67, 3, 4)]
    sum(o.mean() for o in outputs).backward()
    assert all(p.grad is not None for p in model.parameters() if p.requires_grad)
    restored = torch.load(io.BytesIO(_saved(model)))  # picklable as a whole module
    assert type(restored) is type(model)


def _saved(model: nn.Module) -> bytes:
    buffer = io.BytesIO()
    torch.save(model, buffer)
    return buffer.getvalue()


def test_head_bias_initialisation_as_yolov8():
    model = build_detector(ModelConfig("n", 10))
    for box, cls, stride in zip(model.head.box, model.head.cls, (8, 16, 32)):
        assert torch.all(box[-1].bias == 1.0)
        assert torch.allclose(cls[-1].bias, torch.full((10,), math.log(5 / 10 / (640 / stride) ** 2)))


def test_input_size_not_multiple_of_32_is_an_error():
    with pytest.raises(ValueError, match="multiples of 32"):
        build_detector(ModelConfig("n", 2))(torch.rand(1, 3, 64, 80))


def test_bad_config_is_an_error():
    with pytest.raises(ValueError, match="scale"):
        build_detector(ModelConfig("x", 2))
    with pytest.raises(ValueError, match="classes"):
        build_detector(ModelConfig("n", 0))


@pytest.mark.parametrize("training", [True, False])
def test_scale_sequence_conv_equals_conv3d_bn3d_maxpool3d(training):
    """SSFF's 2-D formulation gives exactly ASF-YOLO's 5-D computation (batch statistics included)."""
    torch.manual_seed(1)
    fuse = ScaleSequenceConv3d(6)
    randomize_batch_norms(fuse, 1)
    reference_bn = nn.BatchNorm3d(6, eps=fuse.bn.eps, momentum=fuse.bn.momentum)
    reference_bn.load_state_dict(fuse.bn.state_dict())
    slices = [torch.randn(2, 6, 5, 7) for _ in range(3)]
    fuse.train(training)
    reference_bn.train(training)
    got = fuse(slices)
    stacked = torch.stack(slices, 2)  # [B, C, scales, H, W]
    expected = nn.MaxPool3d((3, 1, 1))(nn.LeakyReLU(0.1)(reference_bn(fuse.conv(stacked)))).squeeze(2)
    assert torch.allclose(got, expected, atol=1e-5)
    assert torch.allclose(fuse.bn.running_mean, reference_bn.running_mean, atol=1e-6)


def test_gd_and_asf_change_the_neck_as_seed_000_describes():
    plain, gd = build_detector(ModelConfig("n", 10)), build_detector(ModelConfig("n", 10, gd_neck=True))
    both = build_detector(ModelConfig("n", 10, gd_neck=True, asf=True))
    names = {n for n, _ in both.named_modules()}
    assert {"neck.low_ifm_in", "neck.inject4", "neck.inject3", "neck.high_ifm", "neck.inject_n4", "neck.inject_n5"} <= names
    assert {"ssff.fuse", "cpam.channel", "cpam.position"} <= names
    assert both.neck.laf4.tfe and not gd.neck.laf4.tfe
    assert measure(plain, (128, 96)).gflops < measure(gd, (128, 96)).gflops < measure(both, (128, 96)).gflops
