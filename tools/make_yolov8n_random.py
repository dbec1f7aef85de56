#!/usr/bin/python3
"""Writes a YOLOv8n-shaped ONNX model with random weights and the raw head, for timing only.

    /usr/bin/python3 tools/make_yolov8n_random.py [OUT.onnx] [--size WxH]
        (needs Debian's python3-torch and python3-onnx; default out/yolov8n_random_raw.onnx)

The layers, channel widths and depths are those of ultralytics' YOLOv8n (yolov8.yaml at scale n:
depth 0.33, width 0.25, 80 classes, 3.2 M parameters), written here from that description, with
batch norm folded into the convolutions as an export does. The head stops before box decoding
and returns the concatenation of the 64 DFL logits and the 80 class logits of every anchor,
1 x 144 x N, exported the way semchain asks users to export their models (README, "Export your
own YOLOv8 model"): opset 12, static shapes, split instead of chunk in C2f. The weights are
random, so the detections mean nothing; bench/detect_bench.cc uses it to time inference.
"""

import argparse
import math
import os

import torch
from torch import nn

REG_MAX = 16


class Conv(nn.Module):
    """Convolution (batch norm folded into its bias) and SiLU."""

    def __init__(self, c1, c2, k=1, s=1):
        super().__init__()
        self.conv = nn.Conv2d(c1, c2, k, s, k // 2, bias=True)
        self.act = nn.SiLU()

    def forward(self, x):
        return self.act(self.conv(x))


class Bottleneck(nn.Module):
    def __init__(self, c1, c2, shortcut):
        super().__init__()
        self.cv1 = Conv(c1, c2, 3)
        self.cv2 = Conv(c2, c2, 3)
        self.add = shortcut and c1 == c2

    def forward(self, x):
        y = self.cv2(self.cv1(x))
        return x + y if self.add else y


class C2f(nn.Module):
    """CSP bottleneck with two convolutions; split() instead of chunk(), which OpenCV 4.6
    cannot load."""

    def __init__(self, c1, c2, n, shortcut):
        super().__init__()
        self.c = c2 // 2
        self.cv1 = Conv(c1, 2 * self.c, 1)
        self.cv2 = Conv((2 + n) * self.c, c2, 1)
        self.m = nn.ModuleList(Bottleneck(self.c, self.c, shortcut) for _ in range(n))

    def forward(self, x):
        y = list(self.cv1(x).split((self.c, self.c), 1))
        for m in self.m:
            y.append(m(y[-1]))
        return self.cv2(torch.cat(y, 1))


class SPPF(nn.Module):
    def __init__(self, c1, c2, k=5):
        super().__init__()
        c = c1 // 2
        self.cv1 = Conv(c1, c, 1)
        self.cv2 = Conv(4 * c, c2, 1)
        self.m = nn.MaxPool2d(k, 1, k // 2)

    def forward(self, x):
        y = [self.cv1(x)]
        for _ in range(3):
            y.append(self.m(y[-1]))
        return self.cv2(torch.cat(y, 1))


class RawDetect(nn.Module):
    """YOLOv8's Detect head without the decoding: per level cat(box DFL logits, class logits),
    flattened and concatenated over the levels. 'hidden' (box, class) overrides the widths of the
    branches' inner convolutions (YOLOv8's own when None)."""

    def __init__(self, nc, channels, hidden=None):
        super().__init__()
        c2, c3 = max(16, channels[0] // 4, 4 * REG_MAX), max(channels[0], min(nc, 100))
        if hidden is not None:
            c2, c3 = hidden
        self.nc = nc
        self.no = 4 * REG_MAX + nc
        self.cv2 = nn.ModuleList(
            nn.Sequential(Conv(c, c2, 3), Conv(c2, c2, 3), nn.Conv2d(c2, 4 * REG_MAX, 1))
            for c in channels)
        self.cv3 = nn.ModuleList(
            nn.Sequential(Conv(c, c3, 3), Conv(c3, c3, 3), nn.Conv2d(c3, nc, 1))
            for c in channels)

    def forward(self, levels):
        outputs = []
        for i, x in enumerate(levels):
            y = torch.cat((self.cv2[i](x), self.cv3[i](x)), 1)
            outputs.append(y.view(1, self.no, -1))
        return torch.cat(outputs, 2)


# YOLOv8n's widths (stem, P2, P3, P4, P5) and C2f repeats (P2, P3, P4, P5 backbone blocks).
YOLOV8N_WIDTHS = (16, 32, 64, 128, 256)
YOLOV8N_REPEATS = (1, 2, 2, 1)


class YoloV8n(nn.Module):
    """YOLOv8's layer graph; by default at scale n. 'widths', 'repeats' and 'head_hidden' make
    narrower variants of the same graph (small test models); 'head' builds the Detect head from
    (nc, channels, hidden)."""

    def __init__(self, nc=80, widths=YOLOV8N_WIDTHS, repeats=YOLOV8N_REPEATS, head_hidden=None,
                 head=RawDetect):
        super().__init__()
        w0, w1, w2, w3, w4 = widths
        self.b0 = Conv(3, w0, 3, 2)
        self.b1 = Conv(w0, w1, 3, 2)
        self.b2 = C2f(w1, w1, repeats[0], True)
        self.b3 = Conv(w1, w2, 3, 2)
        self.b4 = C2f(w2, w2, repeats[1], True)
        self.b5 = Conv(w2, w3, 3, 2)
        self.b6 = C2f(w3, w3, repeats[2], True)
        self.b7 = Conv(w3, w4, 3, 2)
        self.b8 = C2f(w4, w4, repeats[3], True)
        self.b9 = SPPF(w4, w4)
        self.up = nn.Upsample(scale_factor=2.0, mode="nearest")
        self.h12 = C2f(w4 + w3, w3, 1, False)
        self.h15 = C2f(w3 + w2, w2, 1, False)
        self.h16 = Conv(w2, w2, 3, 2)
        self.h18 = C2f(w2 + w3, w3, 1, False)
        self.h19 = Conv(w3, w3, 3, 2)
        self.h21 = C2f(w3 + w4, w4, 1, False)
        self.detect = head(nc, (w2, w3, w4), head_hidden)

    def forward(self, x):
        p3 = self.b4(self.b3(self.b2(self.b1(self.b0(x)))))
        p4 = self.b6(self.b5(p3))
        p5 = self.b9(self.b8(self.b7(p4)))
        h12 = self.h12(torch.cat((self.up(p5), p4), 1))
        h15 = self.h15(torch.cat((self.up(h12), p3), 1))
        h18 = self.h18(torch.cat((self.h16(h15), h12), 1))
        h21 = self.h21(torch.cat((self.h19(h18), p5), 1))
        return self.detect([h15, h18, h21])


def init_weights(model):
    """Random weights that keep activations near unit scale through the network (He normal;
    PyTorch's default init shrinks them layer by layer into float denormals, which are slow and
    would distort the timing), and ultralytics' Detect.bias_init for the class logits, so that
    as with a trained model few anchors pass the confidence threshold."""
    # No two weight tensors may be equal (e.g. all-zero biases): torch.onnx then shares one
    # initializer through Identity nodes, which OpenCV 4.6 cannot load.
    torch.manual_seed(0)
    for m in model.modules():
        if isinstance(m, nn.Conv2d):
            nn.init.kaiming_normal_(m.weight, nonlinearity="relu")
            nn.init.normal_(m.bias, std=0.01)
    head = model.detect
    for box, cls, stride in zip(head.cv2, head.cv3, (8, 16, 32)):
        nn.init.normal_(box[-1].weight, std=0.01)
        nn.init.normal_(box[-1].bias, mean=1.0, std=0.01)
        nn.init.normal_(cls[-1].weight, std=0.01)
        nn.init.normal_(cls[-1].bias, mean=math.log(5 / head.nc / (640 / stride) ** 2), std=0.01)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out/yolov8n_random_raw.onnx")
    parser.add_argument("--size", default="640x640", help="static input WIDTHxHEIGHT")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    model = YoloV8n().eval()
    init_weights(model)
    print(f"parameters: {sum(p.numel() for p in model.parameters()) / 1e6:.2f} M")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with torch.no_grad():
        torch.onnx.export(model, torch.zeros(1, 3, height, width), args.out, opset_version=12,
                          input_names=["images"], output_names=["output0"],
                          do_constant_folding=True)
    names = os.path.splitext(args.out)[0] + ".names"
    with open(names, "w") as f:
        f.write("".join(f"class{i}\n" for i in range(80)))
    print(f"wrote {args.out} and {names}")


if __name__ == "__main__":
    main()
