import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import torch

from semchain_train.checkpoint import load_checkpoint, save_checkpoint
from oracle_detector import OracleDetector
from synthetic_data import CLASS_NAMES, four_colour_dataset

TESTS_DIR = Path(__file__).resolve().parent
TRAIN_DIR = TESTS_DIR.parent


def run_cli(*args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=f"{TRAIN_DIR}{os.pathsep}{TESTS_DIR}", OMP_NUM_THREADS="1")
    return subprocess.run(
        [sys.executable, "-m", "semchain_train", *args], capture_output=True, text=True, env=env, cwd=TESTS_DIR, timeout=300
    )


def run_in_process(*args: str) -> subprocess.CompletedProcess:
    """main() in this process (no interpreter start-up), its stderr and exit status as run_cli gives them."""
    import contextlib
    import io

    from semchain_train.__main__ import main

    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        try:
            code = main(list(args))
        except SystemExit as exit:
            code = exit.code
    return subprocess.CompletedProcess(args, code, stdout.getvalue(), stderr.getvalue())


def assert_one_line_error(result: subprocess.CompletedProcess, *fragments: str) -> None:
    assert result.returncode == 1, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("semchain_train: error: "), result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


@pytest.mark.parametrize("command", ["train", "val", "prune", "export"])
def test_every_subcommand_has_help(command: str) -> None:
    result = run_in_process(command, "--help")
    assert result.returncode == 0 and "usage: semchain_train " + command in result.stdout


def test_missing_data_yaml(tmp_path: Path) -> None:
    result = run_cli("train", "--data", str(tmp_path / "nope.yaml"), "--out", str(tmp_path / "run"))
    assert_one_line_error(result, "nope.yaml: no such data.yaml")


def test_class_count_disagreeing_with_names(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path)
    data.write_text(data.read_text().replace("nc: 4", "nc: 5"))
    assert_one_line_error(run_in_process("train", "--data", str(data), "--out", str(tmp_path / "run")), "nc is 5 but names lists 4")


def test_split_without_images(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path)
    for image in (tmp_path / "images" / "val").iterdir():
        image.unlink()
    result = run_in_process("train", "--data", str(data), "--out", str(tmp_path / "run"), "--input", "64x64")
    assert_one_line_error(result, "no images in the val split")


def test_bad_label_line_names_file_and_line(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path)
    (tmp_path / "labels" / "train" / "002.txt").write_text("2 0.5 0.5 0.2 0.2\n1 0.5 0.5 1.2 0.2\n")
    result = run_in_process("train", "--data", str(data), "--out", str(tmp_path / "run"), "--input", "64x64")
    assert_one_line_error(result, "labels/train/002.txt:2: '1.2' lies outside [0, 1]")


def test_unknown_device_and_bad_sizes(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path)
    assert_one_line_error(run_in_process("train", "--data", str(data), "--out", str(tmp_path / "r"), "--device", "tpu"), "device 'tpu'")
    assert_one_line_error(run_in_process("train", "--data", str(data), "--out", str(tmp_path / "r"), "--input", "320x250"),
                          "multiples of 32")
    assert_one_line_error(run_in_process("val", "--weights", str(tmp_path / "w.pt"), "--data", str(data)), "w.pt: no such checkpoint")


def test_val_of_a_corrupt_checkpoint(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path)
    (tmp_path / "bad.pt").write_bytes(b"not a checkpoint")
    assert_one_line_error(run_in_process("val", "--weights", str(tmp_path / "bad.pt"), "--data", str(data)), "bad.pt: not a readable checkpoint")


def test_val_writes_the_metrics(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path, splits=("val", "test"))
    weights = save_checkpoint(tmp_path / "oracle.pt", OracleDetector(), names=CLASS_NAMES, epoch=0,
                              train_options={"input_size": (64, 64)})
    result = run_cli("val", "--weights", str(weights), "--data", str(data), "--out", str(tmp_path / "r.json"), "--no-progress")
    assert result.returncode == 0, result.stderr
    values = json.loads((tmp_path / "r.json").read_text())
    assert values["map50"] == 1.0 and values["images"] == 4 and values["input"] == "64x64" and values["split"] == "test"
    assert "mAP@0.5 1.0000" in result.stdout
    wrong = save_checkpoint(tmp_path / "wrong.pt", OracleDetector(), names=["a", "b", "c", "d"], epoch=0)
    assert_one_line_error(run_in_process("val", "--weights", str(wrong), "--data", str(data)), "are not")


def test_train_then_resume_an_n_model(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path / "data")
    run = tmp_path / "run"
    common = ("--input", "64x64", "--batch", "2", "--workers", "0", "--threads", "1", "--no-progress")
    first = run_cli("train", "--data", str(data), "--out", str(run), "--scale", "n", "--epochs", "1", *common)
    assert first.returncode == 0, first.stderr
    assert (run / "best.pt").exists() and (run / "results.csv").exists() and (run / "args.yaml").exists()
    checkpoint = load_checkpoint(run / "last.pt")
    assert checkpoint.epoch == 0 and checkpoint.raw["config"].scale == "n" and checkpoint.names == CLASS_NAMES
    outputs = checkpoint.model(torch.rand(1, 3, 64, 64))
    assert [tuple(o.shape) for o in outputs] == [(1, 68, 8, 8), (1, 68, 4, 4), (1, 68, 2, 2)]
    # Resuming a finished run trains nothing more and keeps the weights.
    again = run_cli("train", "--data", str(data), "--out", str(run), "--resume", *common)
    assert again.returncode == 0, again.stderr
    after = load_checkpoint(run / "last.pt")
    assert after.epoch == 0
    assert all(torch.equal(a, b) for a, b in zip(checkpoint.model.state_dict().values(), after.model.state_dict().values()))
    # A next stage starts from the run's best.pt (its EMA weights) and trains them.
    stage = tmp_path / "stage"
    next_stage = run_cli("train", "--data", str(data), "--out", str(stage), "--weights", str(run / "best.pt"), "--epochs", "1",
                         "--lr0", "0.01", *common)
    assert next_stage.returncode == 0, next_stage.stderr
    trained = load_checkpoint(stage / "last.pt").raw["model"]
    started = load_checkpoint(run / "best.pt").model
    assert any(not torch.equal(a, b) for a, b in zip(started.state_dict().values(), trained.state_dict().values()))
