from pathlib import Path

import numpy as np
import pytest

from semchain_train.data.augment import fit_letterbox
from semchain_train.metrics import DetectionEvaluator, average_precision, box_iou_matrix
from semchain_train.val import EvalOptions, class_wise_nms, evaluate, fitness, postprocess
from oracle_detector import OracleDetector
from synthetic_data import four_colour_dataset

import torch


def _det(x1, y1, x2, y2, score, cls):
    return [x1, y1, x2, y2, score, cls]


def test_iou_of_known_boxes() -> None:
    iou = box_iou_matrix(np.array([[0, 0, 10, 10]]), np.array([[0, 0, 10, 10], [5, 0, 15, 10], [10, 0, 20, 10]]))
    np.testing.assert_allclose(iou, [[1.0, 50 / 150, 0.0]])


def test_perfect_detections_score_one_and_classes_without_truth_are_ignored() -> None:
    evaluator = DetectionEvaluator(3)
    evaluator.add_image(np.array([_det(0, 0, 10, 10, 0.9, 0), _det(20, 20, 40, 50, 0.3, 2)]),
                        np.array([[0, 0, 0, 10, 10], [2, 20, 20, 40, 50]]))
    accuracy = evaluator.evaluate()
    assert accuracy.map50 == 1.0 and abs(accuracy.map50_95 - 1.0) < 1e-12
    assert accuracy.precision == 1.0 and accuracy.recall == 1.0 and accuracy.classes[1].truths == 0


def test_false_positive_ranked_first_halves_the_ap_of_a_single_truth() -> None:
    # Precision 0, 1/2 at recall 0, 1: the envelope is 1/2 everywhere -> AP 0.5.
    evaluator = DetectionEvaluator(1)
    evaluator.add_image(np.array([_det(50, 50, 60, 60, 0.9, 0), _det(0, 0, 10, 10, 0.8, 0)]), np.array([[0, 0, 0, 10, 10]]))
    accuracy = evaluator.evaluate()
    assert abs(accuracy.map50 - 0.5) < 1e-12
    # Best F1: above 0.9 nothing (F1 0); 0.8 < c <= 0.9 keeps the FP only (P 0); c <= 0.8: P 1/2, R 1.
    assert abs(accuracy.precision - 0.5) < 1e-12 and accuracy.recall == 1.0


def test_false_positive_between_two_hits() -> None:
    # TP, FP, TP over 2 truths: precision 1, 1/2, 2/3 at recall 1/2, 1/2, 1;
    # envelope 1 for recall 0..0.5 (51 points), 2/3 for 0.51..1 (50 points).
    evaluator = DetectionEvaluator(1)
    detections = np.array([_det(0, 0, 10, 10, 0.9, 0), _det(50, 50, 60, 60, 0.8, 0), _det(20, 0, 30, 10, 0.7, 0)])
    evaluator.add_image(detections, np.array([[0, 0, 0, 10, 10], [0, 20, 0, 30, 10]]))
    assert abs(evaluator.evaluate().map50 - (51 + 50 * 2 / 3) / 101) < 1e-12


def test_a_box_of_known_iou_counts_only_up_to_that_threshold() -> None:
    # Truth 10 x 10, prediction 10 x 7.2 inside it: IoU 0.72 -> hits at 0.50 ... 0.70 (5 of 10).
    evaluator = DetectionEvaluator(1)
    evaluator.add_image(np.array([_det(0, 0, 10, 7.2, 0.5, 0)]), np.array([[0, 0, 0, 10, 10]]))
    accuracy = evaluator.evaluate()
    assert accuracy.map50 == 1.0 and abs(accuracy.map50_95 - 0.5) < 1e-12


def test_duplicates_wrong_classes_and_misses() -> None:
    evaluator = DetectionEvaluator(2)
    detections = np.array([_det(0, 0, 10, 10, 0.9, 0), _det(0, 0, 10, 10, 0.8, 0), _det(0, 0, 10, 10, 0.95, 1)])
    evaluator.add_image(detections, np.array([[0, 0, 0, 10, 10], [0, 50, 50, 60, 60]]))
    accuracy = evaluator.evaluate()
    # Class 0: precision 1, 1/2 at recall 1/2 -> AP 51/101; class 1 has no truth (its box is not averaged).
    assert abs(accuracy.map50 - 51 / 101) < 1e-12
    assert accuracy.recall == 0.5 and accuracy.precision == 1.0


def test_greedy_matching_takes_the_best_iou_truth() -> None:
    # One detection overlapping two truths (IoU 0.6 and 0.9): it takes the 0.9 one, the next detection
    # (exactly on the first truth) still finds its truth.
    evaluator = DetectionEvaluator(1)
    truths = np.array([[0, 0, 0, 10, 10], [0, 2.5, 0, 12.5, 10]])
    detections = np.array([_det(1.5, 0, 11.5, 10, 0.9, 0), _det(0, 0, 10, 10, 0.8, 0)])
    assert abs(box_iou_matrix(detections[:1, :4], truths[1:, 1:])[0, 0] - 90 / 110) < 1e-12
    evaluator.add_image(detections, truths)
    assert evaluator.evaluate().map50 == 1.0


def test_average_precision_of_no_detections_is_zero() -> None:
    assert average_precision(np.array([]), np.array([])) == 0.0
    evaluator = DetectionEvaluator(1)
    evaluator.add_image(np.zeros((0, 6)), np.array([[0, 0, 0, 10, 10]]))
    accuracy = evaluator.evaluate()
    assert accuracy.map50 == 0.0 and accuracy.recall == 0.0


def test_nms_is_class_wise_and_keeps_the_best_first() -> None:
    boxes = np.array([[0, 0, 10, 10], [0, 0, 10, 9], [0, 0, 10, 10], [0, 0, 10, 5], [30, 30, 40, 40]], float)
    scores = np.array([0.5, 0.9, 0.7, 0.6, 0.2])
    classes = np.array([0, 0, 1, 0, 0])
    # 1 (0.9) suppresses 0 (IoU 0.9 > 0.7); 3 (IoU 5/9 with 1) stays; 2 is another class.
    assert class_wise_nms(boxes, scores, classes, 0.7, 300).tolist() == [1, 2, 3, 4]
    assert class_wise_nms(boxes, scores, classes, 0.7, 2).tolist() == [1, 2]


def test_postprocess_maps_input_boxes_back_through_the_letterbox() -> None:
    letterbox = fit_letterbox((128, 64), (64, 64))  # scale 0.5, 16 px padding above
    boxes = torch.tensor([[4.0, 20.0, 14.0, 30.0], [0.0, 0.0, 1.0, 10.0], [-8.0, 12.0, 8.0, 40.0]])
    scores = torch.tensor([[0.1, 0.8], [0.0005, 0.0002], [0.3, 0.2]])
    out = postprocess(boxes, scores, letterbox, EvalOptions(input_size=(64, 64)))
    np.testing.assert_allclose(out, [[8, 8, 28, 28, 0.8, 1], [0, 0, 16, 48, 0.3, 0]])


@pytest.mark.parametrize("size", [(64, 64), (80, 64)])
def test_oracle_detections_score_one(tmp_path: Path, size) -> None:
    data = four_colour_dataset(tmp_path, size=size, splits=("val",))
    result = evaluate(OracleDetector(), data, split="val", input_size=(64, 64))
    assert result["images"] == 4 and result["truths"] == 4
    assert result["map50"] == 1.0 and result["precision"] == 1.0 and result["recall"] == 1.0
    if size == (64, 64):  # no resampling: exact boxes
        assert abs(result["map50_95"] - 1.0) < 1e-9
        assert abs(fitness(result) - 1.0) < 1e-9
    assert list(result["classes"]) == ["red", "green", "blue", "yellow"]


def test_oracle_boxes_of_known_iou(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path, splits=("val",))
    result = evaluate(OracleDetector(height_factor=0.72), data, split="val", input_size=(64, 64))
    assert result["map50"] == 1.0 and abs(result["map50_95"] - 0.5) < 1e-9
