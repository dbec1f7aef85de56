#!/usr/bin/python3
"""Writes the tiny YOLOv8-format test models of src/detection/testdata (no training).

    /usr/bin/python3 tools/make_tiny_yolo.py [OUT_DIR]   (needs Debian's python3-onnx, python3-numpy)

The models "detect" filled axis-aligned rectangles of pure red, green and blue (255 on one RGB
channel, 0 on the others) with hand-set weights, and report their boxes exactly:

  tiny_squares_raw.onnx      raw head, 1 x (64 + 3) x N: DFL logits of the distances left, top,
                             right, bottom (16 bins each), then the class logits (before sigmoid)
  tiny_squares_decoded.onnx  decoded head, 1 x (4 + 3) x N: cx, cy, w, h in input pixels, then
                             the class scores (after sigmoid)
  unflattened_head.onnx      a broken export for the error tests: the stride-8 raw head alone,
                             not flattened (1 x 67 x H/8 x W/8)
  tiny_squares_attention.onnx  tiny_squares_raw with an unused MatMul of two computed tensors
                             (OpenCV 4.6's FLOPs count reads weights such a MatMul does not have)

with N anchors of the strides 8, 16 and 32, row-major per stride, anchor centres at
((i + 0.5) * stride, (j + 0.5) * stride), as ultralytics YOLOv8 lays them out. Every op is one
that OpenCV 4.6 DNN runs (Conv with groups and asymmetric pads, Relu, Add, Log, Sigmoid,
Concat, Reshape), opset 12, and no layer depends on the input size: any width and height that are
multiples of 32 work (the decoded model up to 1024 pixels a side).

How the weights make the boxes exact, per stride s and anchor (ax, ay):
  1. masks: M_c = clamp(4 (x_c - sum of the other channels) - 1, 0, 1) per class, U = sum_c M_c.
  2. the anchor's pixel row and column are picked out by strided one-hot convolutions and cut
     into blocks of s pixels; from the blocks' mask shares (grid units) the run of mask pixels
     from the anchor to the rectangle's edge is summed, block by block up to the first block
     that is not full (run_lengths): for an anchor inside a rectangle exactly its distances to
     the edges, up to 15 strides.
  3. a distance t becomes 16 bin weights w_k = max(0, 1 - |t - k|) (a "hat": two neighbouring
     bins share the weight, so sum_k k w_k = t and sum_k w_k = 1 for t in [0, 15]), built as
     relu(t - k + 1) - 2 relu(t - k) + relu(t - k - 1). The logits are log(w_k + 1e-7), so the
     decoder's softmax gives back w (to 1e-7) and its expectation gives back t.
  4. the class logit is +10 where the anchor's pixel has the class's colour and all four edges
     are within reach (t < 15), else -10 or less.
Limits (a test model, not a detector): rectangle edges must fall on whole pixels of the network
input (after a 2x letterbox downscale: even image coordinates), rectangles in the same rows
(columns) must be at least 32 input pixels apart, and every anchor inside a rectangle fires
with the same box, so the detector's NMS must merge them.
"""

import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

CLASSES = ["red_square", "green_square", "blue_square"]
STRIDES = [8, 16, 32]
REG_MAX = 16
REACH = 15            # largest distance in strides the 16 bins can express
CUMULATIVE_BLOCKS = 128  # anchor coordinates of the decoded model: up to 128 cells a row
EPSILON = 1e-7


class Graph:
    """Collects nodes and initializers with unique names."""

    def __init__(self):
        self.nodes = []
        self.initializers = []
        self.count = 0
        self.shared = {}  # bytes of a constant -> its name: strides share their head weights
        self.channels = {}  # channel counts of the tensors run_lengths reads

    def name(self, stem):
        self.count += 1
        return f"{stem}_{self.count}"

    def const(self, stem, array, dtype=np.float32):
        array = np.asarray(array, dtype=dtype)
        key = (array.shape, array.tobytes())
        if key not in self.shared:
            self.shared[key] = self.name(stem)
            self.initializers.append(numpy_helper.from_array(array, self.shared[key]))
        return self.shared[key]

    def op(self, op_type, inputs, stem, **attributes):
        output = self.name(stem)
        self.nodes.append(helper.make_node(op_type, inputs, [output], name=output, **attributes))
        return output

    def conv(self, x, weight, bias=None, stem="conv", **attributes):
        inputs = [x, self.const(stem + "_w", weight)]
        if bias is not None:
            inputs.append(self.const(stem + "_b", bias))
        kernel = list(np.asarray(weight).shape[2:])
        return self.op("Conv", inputs, stem, kernel_shape=kernel, **attributes)


def masks(g, x, with_ones):
    """Channels M_0..M_nc-1, U (and a channel of ones for the decoded model's anchors)."""
    nc = len(CLASSES)
    w = np.zeros((2 * nc, 3, 1, 1))
    b = np.zeros(2 * nc)
    for c in range(nc):
        v = -np.ones(3)
        v[c] = 1.0
        w[c, :, 0, 0] = 4.0 * v
        w[nc + c, :, 0, 0] = 4.0 * v
        b[c], b[nc + c] = -1.0, -2.0
    ramps = g.op("Relu", [g.conv(x, w, b, "colour")], "colour_relu")
    channels = nc + 2 if with_ones else nc + 1
    w2 = np.zeros((channels, 2 * nc, 1, 1))
    b2 = np.zeros(channels)
    for c in range(nc):
        w2[c, c], w2[c, nc + c] = 1.0, -1.0
        w2[nc, c], w2[nc, nc + c] = 1.0, -1.0
    if with_ones:
        b2[nc + 1] = 1.0
    return g.conv(ramps, w2, b2, "masks"), channels


def stride_features(g, m, channels, s, with_ones):
    """Distances l, t, r, b (grid units), class colour at the anchor, and anchor x, y."""
    nc, h = len(CLASSES), s // 2
    u, ones = nc, nc + 1
    pick_row = np.zeros((channels, 1, h + 1, 1))
    pick_row[:, 0, h, 0] = 1.0
    rows = g.conv(m, pick_row, None, "rows", group=channels, strides=[s, 1])
    pick_col = np.zeros((channels, 1, 1, h + 1))
    pick_col[:, 0, 0, h] = 1.0
    cols = g.conv(m, pick_col, None, "cols", group=channels, strides=[1, s])

    pick_inside = np.zeros((nc, channels, 1, h + 1))
    for c in range(nc):
        pick_inside[c, c, 0, h] = 1.0
    inside = g.conv(rows, pick_inside, None, "inside", strides=[1, s])

    # Block sums: cell i holds the pixels of [ax_i - s, ax_i) (grid units), and for the ones
    # channel the pixel count itself.
    sums = 2 if with_ones else 1
    block_x = np.zeros((sums, channels, 1, s))
    block_x[0, u, 0, :] = 1.0 / s
    block_y = np.zeros((sums, channels, s, 1))
    block_y[0, u, :, 0] = 1.0 / s
    if with_ones:
        block_x[1, ones, 0, :] = 1.0
        block_y[1, ones, :, 0] = 1.0
    sx = g.conv(rows, block_x, None, "block_x", strides=[1, s], pads=[0, h, 0, 0])
    sy = g.conv(cols, block_y, None, "block_y", strides=[s, 1], pads=[h, 0, 0, 0])
    g.channels[sx] = g.channels[sy] = sums
    # The blocks [ax_i, ax_i + s) after each anchor: the last one reaches into the zero padding,
    # so that a rectangle touching the right (bottom) border is measured whole.
    after_x = np.zeros((1, channels, 1, s + h))
    after_x[0, u, 0, h:] = 1.0 / s
    tx = g.conv(rows, after_x, None, "after_x", strides=[1, s], pads=[0, 0, 0, h])
    ty = g.conv(cols, after_x.transpose(0, 1, 3, 2), None, "after_y", strides=[s, 1],
                pads=[0, 0, h, 0])
    g.channels[tx] = g.channels[ty] = 1

    left, right = run_lengths(g, sx, tx, s, vertical=False)
    top, bottom = run_lengths(g, sy, ty, s, vertical=True)
    ltrb = g.op("Concat", [left, top, right, bottom], "ltrb", axis=1)

    anchors = None
    if with_ones:
        n = CUMULATIVE_BLOCKS
        cum_x = np.zeros((1, sums, 1, n))
        cum_x[0, 1, 0, :] = 1.0
        cum_y = np.zeros((1, sums, n, 1))
        cum_y[0, 1, :, 0] = 1.0
        ax = g.conv(sx, cum_x, None, "anchor_x", pads=[0, n - 1, 0, 0])
        ay = g.conv(sy, cum_y, None, "anchor_y", pads=[n - 1, 0, 0, 0])
        anchors = (ax, ay)
    return ltrb, inside, anchors


def run_lengths(g, before, after, s, vertical):
    """The mask's run lengths (grid units) before and after the anchor along a row (column).

    Channel 0 of 'before' holds S_i, the share of mask pixels in the block of s pixels just
    before anchor i (grid units), channel 0 of 'after' that of the block just after it. Going
    away from the anchor, the distance to the rectangle's edge is the sum of S over the blocks
    up to and including the first block that is not full: d = sum_j P_j S_(i-j), where
    P_j = F_i ... F_(i-j+1) is 1 while all blocks nearer than j are full (F = 1 iff S = 1).
    P_j, an AND of j bits, is relu(sum of the bits - (j - 1)); P_j S = relu(S + P_j - 1). So
    pixels of another rectangle count only when they share the edge block (closer than s).
    """

    def kernel(weights):  # horizontal (out, in, 1, k) -> vertical (out, in, k, 1)
        return weights.transpose(0, 1, 3, 2) if vertical else weights

    def pads(first, last):
        return [first, 0, last, 0] if vertical else [0, first, 0, last]

    distances = []
    for blocks, toward_start in ((before, True), (after, False)):
        channels = g.channels[blocks]
        full_w = np.zeros((1, channels, 1, 1))
        full_w[0, 0] = s  # F = relu(s S - (s - 1)): 1 for s pixels of s, else 0
        full = g.op("Relu", [g.conv(blocks, full_w, [-(s - 1.0)], "full")], "full_relu")

        # Kernel tap t covers block i - (REACH - 1) + t (before) or i + t (after).
        def tap(m):  # tap of the block m steps away from the anchor
            return REACH - 1 - m if toward_start else m
        pad = pads(REACH - 1, 0) if toward_start else pads(0, REACH - 1)
        p_w = np.zeros((REACH, 1, 1, REACH))
        p_b = np.zeros(REACH)
        for j in range(REACH):
            for m in range(j):
                p_w[j, 0, 0, tap(m)] = 1.0
            p_b[j] = 1.0 - j
        prefix = g.op("Relu", [g.conv(full, kernel(p_w), p_b, "prefix", pads=pad)], "prefix_relu")
        s_w = np.zeros((REACH, channels, 1, REACH))
        for j in range(REACH):
            s_w[j, 0, 0, tap(j)] = 1.0
        shifted = g.conv(blocks, kernel(s_w), np.full(REACH, -1.0), "shifted", pads=pad)
        terms = g.op("Relu", [g.op("Add", [shifted, prefix], "terms_sum")], "terms")
        distances.append(g.conv(terms, np.ones((1, REACH, 1, 1)), None, "distance"))
    return distances


def class_logits(g, ltrb, inside):
    """+10 where the anchor has the class's colour and every edge is within reach."""
    nc = len(CLASSES)
    features = g.op("Concat", [ltrb, inside], "cls_in", axis=1)
    w = np.zeros((8 + nc, 4 + nc, 1, 1))
    b = np.zeros(8 + nc)
    for d in range(4):  # ok_d = clamp(32 (15 - t_d), 0, 1): 1 for t_d <= 15 - 1/32
        w[d, d], b[d] = -32.0, 32.0 * REACH
        w[4 + d, d], b[4 + d] = -32.0, 32.0 * REACH - 1.0
    for c in range(nc):
        w[8 + c, 4 + c] = 1.0
    ramps = g.op("Relu", [g.conv(features, w, b, "cls_ramps")], "cls_relu")
    w2 = np.zeros((nc, 8 + nc, 1, 1))
    for c in range(nc):
        w2[c, 0:4], w2[c, 4:8], w2[c, 8 + c] = 20.0, -20.0, 20.0
    return g.conv(ramps, w2, np.full(nc, -90.0), "cls_logits")


def dfl_logits(g, ltrb):
    """64 channels, side-major in the order l, t, r, b: log of the hat weights of the bins."""
    w = np.ones((4 * REG_MAX * 3, 1, 1, 1))
    b = np.zeros(4 * REG_MAX * 3)
    for side in range(4):
        for k in range(REG_MAX):
            for j, offset in enumerate((1.0, 0.0, -1.0)):
                b[(side * REG_MAX + k) * 3 + j] = offset - k
    ramps = g.op("Relu", [g.conv(ltrb, w, b, "dfl_ramps", group=4)], "dfl_relu")
    hat = np.tile(np.array([1.0, -2.0, 1.0]).reshape(1, 3, 1, 1), (4 * REG_MAX, 1, 1, 1))
    weights = g.conv(ramps, hat, np.full(4 * REG_MAX, EPSILON), "dfl_hat", group=4 * REG_MAX)
    return g.op("Log", [weights], "dfl_log")


def decoded_boxes(g, ltrb, anchors, s):
    """cx, cy, w, h in input pixels from the distances (grid units) and anchor centres."""
    features = g.op("Concat", [ltrb, anchors[0], anchors[1]], "xywh_in", axis=1)
    w = np.zeros((4, 6, 1, 1))
    w[0, 4], w[0, 0], w[0, 2] = 1.0, -s / 2, s / 2  # cx = ax + s (r - l) / 2
    w[1, 5], w[1, 1], w[1, 3] = 1.0, -s / 2, s / 2  # cy = ay + s (b - t) / 2
    w[2, 0], w[2, 2] = s, s  # w = s (l + r)
    w[3, 1], w[3, 3] = s, s  # h = s (t + b)
    return g.conv(features, w, None, "xywh")


def attention_product(g, m, channels):
    """A MatMul of two computed tensors, as attention blocks (Gold-YOLO's High-IFM) have:
    (1 x C x 1) @ (1 x 1 x C) of the masks' channel means. Its result feeds nothing, so the boxes
    stay those of the model without it."""
    pooled = g.op("GlobalAveragePool", [m], "attention_pool")
    column = g.op("Reshape", [pooled, g.const("column", [1, channels, 1], np.int64)], "attention_q")
    row = g.op("Reshape", [pooled, g.const("row", [1, 1, channels], np.int64)], "attention_k")
    return g.op("MatMul", [column, row], "attention")


def build(decoded, width=640, height=640, unflattened=False, attention=False):
    """The test model; 'unflattened' gives a broken export instead: the stride-8 head alone,
    1 x (64 + nc) x H/8 x W/8, to test that the detector rejects an output of the wrong shape;
    'attention' adds attention_product beside it."""
    g = Graph()
    nc = len(CLASSES)
    m, channels = masks(g, "images", decoded)
    if attention:
        attention_product(g, m, channels)
    heads = []
    for s in STRIDES[:1] if unflattened else STRIDES:
        ltrb, inside, anchors = stride_features(g, m, channels, s, decoded)
        logits = class_logits(g, ltrb, inside)
        if decoded:
            parts = [decoded_boxes(g, ltrb, anchors, s), g.op("Sigmoid", [logits], "scores")]
        else:
            parts = [dfl_logits(g, ltrb), logits]
        head = g.op("Concat", parts, "head", axis=1)
        if unflattened:
            heads.append(head)
            continue
        rows = (4 if decoded else 4 * REG_MAX) + nc
        shape = g.const("shape", [1, rows, -1], np.int64)
        heads.append(g.op("Reshape", [head, shape], "flat"))
    rows = (4 if decoded else 4 * REG_MAX) + nc
    if unflattened:
        out, shape = heads[0], [1, rows, height // STRIDES[0], width // STRIDES[0]]
    else:
        out = g.op("Concat", heads, "output0", axis=2)
        shape = [1, rows, sum((width // s) * (height // s) for s in STRIDES)]
    graph = helper.make_graph(
        g.nodes, "tiny_squares_decoded" if decoded else "tiny_squares_raw",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, height, width])],
        [helper.make_tensor_value_info(out, TensorProto.FLOAT, shape)], g.initializers)
    model = helper.make_model(graph, producer_name="semchain tools/make_tiny_yolo.py",
                              opset_imports=[helper.make_opsetid("", 12)])
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "src", "detection", "testdata")
    os.makedirs(out_dir, exist_ok=True)
    for decoded, stem in ((False, "tiny_squares_raw"), (True, "tiny_squares_decoded")):
        path = os.path.join(out_dir, stem + ".onnx")
        onnx.save(build(decoded), path)
        with open(os.path.join(out_dir, stem + ".names"), "w") as names:
            names.write("\n".join(CLASSES) + "\n")
        print(f"wrote {path} ({os.path.getsize(path)} bytes)")
    path = os.path.join(out_dir, "unflattened_head.onnx")
    onnx.save(build(False, unflattened=True), path)
    print(f"wrote {path} ({os.path.getsize(path)} bytes)")
    path = os.path.join(out_dir, "tiny_squares_attention.onnx")
    onnx.save(build(False, attention=True), path)
    print(f"wrote {path} ({os.path.getsize(path)} bytes)")


if __name__ == "__main__":
    main()
