import csv
from pathlib import Path

import pytest
import torch

from semchain_train.checkpoint import load_checkpoint
from semchain_train.train import TrainError, TrainOptions, fit
from stand_in_detector import StandInConfig, StandInDetector
from synthetic_data import CLASS_NAMES, four_colour_dataset, write_dataset


class Interrupted(Exception):
    pass


def _options(data: Path, out: Path, **overrides) -> TrainOptions:
    values = dict(
        data=data, out=out, epochs=3, batch=2, input_size=(64, 64), warmup_epochs=1, close_mosaic=1,
        workers=0, progress=False, seed=3, nominal_batch=4, lr0=0.01, threads=1,
    )
    values.update(overrides)
    return TrainOptions(**values)


def _model() -> StandInDetector:
    torch.manual_seed(0)
    return StandInDetector(StandInConfig(classes=4))


def _two_image_data(root: Path) -> Path:
    rects = {"train": [[(0, (8, 8, 40, 40)), (2, (44, 20, 60, 60))], [(1, (10, 30, 50, 62))]],
             "val": [[(0, (8, 8, 40, 40))], [(3, (20, 4, 60, 30))]]}
    return write_dataset(root, rects)


def _same_final_weights(straight: Path, resumed: Path) -> tuple[dict, dict]:
    """The two run folders' last.pt (raw), asserted to hold the same model and EMA weights."""
    a = load_checkpoint(straight / "last.pt").raw
    b = load_checkpoint(resumed / "last.pt").raw
    assert a["epoch"] == b["epoch"] == 2 and a["ema_updates"] == b["ema_updates"] > 0
    for key in ("model", "ema"):
        sa, sb = a[key].state_dict(), b[key].state_dict()
        assert all(torch.equal(sa[name], sb[name]) for name in sa), key
    return a, b


def test_resume_after_an_interrupted_epoch_gives_the_same_weights(tmp_path: Path) -> None:
    data = _two_image_data(tmp_path / "data")
    straight = fit(_model(), _options(data, tmp_path / "straight"), CLASS_NAMES)

    def interrupt(epoch: int, iteration: int) -> None:
        if epoch == 2:
            raise Interrupted

    with pytest.raises(Interrupted):
        fit(_model(), _options(data, tmp_path / "resumed"), CLASS_NAMES, on_batch_end=interrupt)
    assert load_checkpoint(tmp_path / "resumed" / "last.pt").epoch == 1
    fit(_model(), _options(data, tmp_path / "resumed", resume=True), CLASS_NAMES)

    a, b = _same_final_weights(straight.parent, tmp_path / "resumed")
    assert a["best_fitness"] == b["best_fitness"]
    rows = list(csv.DictReader((tmp_path / "resumed" / "results.csv").open()))
    assert [r["epoch"] for r in rows] == ["1", "2", "3"]
    # The weights moved: training happened at all.
    start = _model().state_dict()
    assert not all(torch.equal(start[n], a["model"].state_dict()[n]) for n in start)


def test_resume_within_an_epoch_gives_the_same_weights(tmp_path: Path) -> None:
    # Four images, batch 1, two batches per optimizer step: last.pt is written after the step that
    # ends the second batch of each epoch; stopped in the third batch of the second epoch, the run
    # goes on from there, not from the epoch's start.
    data = four_colour_dataset(tmp_path / "data")
    overrides = dict(batch=1, nominal_batch=2, warmup_epochs=0, checkpoint_batches=2)
    straight = fit(_model(), _options(data, tmp_path / "straight", **overrides), CLASS_NAMES)

    def interrupt(epoch: int, iteration: int) -> None:
        if (epoch, iteration) == (1, 2):
            raise Interrupted

    with pytest.raises(Interrupted):
        fit(_model(), _options(data, tmp_path / "resumed", **overrides), CLASS_NAMES, on_batch_end=interrupt)
    saved = load_checkpoint(tmp_path / "resumed" / "last.pt")
    assert saved.epoch == 0 and saved.raw["extra"]["partial"]["batches"] == 2
    seen: list[tuple[int, int]] = []
    fit(_model(), _options(data, tmp_path / "resumed", resume=True, **overrides), CLASS_NAMES,
        on_batch_end=lambda epoch, iteration: seen.append((epoch, iteration)))
    assert seen[0] == (1, 2)  # the two batches done are not done again

    a, b = _same_final_weights(straight.parent, tmp_path / "resumed")
    assert not b["extra"]["partial"]
    rows = list(csv.DictReader((tmp_path / "resumed" / "results.csv").open()))
    straight_rows = list(csv.DictReader((tmp_path / "straight" / "results.csv").open()))
    assert [r["epoch"] for r in rows] == ["1", "2", "3"]
    assert [r["box_loss"] for r in rows] == [r["box_loss"] for r in straight_rows]


def test_fit_writes_the_run_folder(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path / "data")
    best = fit(_model(), _options(data, tmp_path / "run", epochs=2, eval_every=5), CLASS_NAMES)
    assert best == tmp_path / "run" / "best.pt" and best.exists()
    for name in ("last.pt", "results.csv", "args.yaml"):
        assert (tmp_path / "run" / name).exists()
    rows = list(csv.DictReader((tmp_path / "run" / "results.csv").open()))
    assert rows[0]["map50"] == "" and rows[1]["map50"] != ""  # validated after the last epoch only
    loaded = load_checkpoint(best)
    assert loaded.names == CLASS_NAMES and loaded.raw["train_options"]["input_size"] == (64, 64)
    assert not [p for p in (tmp_path / "run").iterdir() if p.name.endswith(".tmp")]


def test_bad_options_are_refused(tmp_path: Path) -> None:
    data = four_colour_dataset(tmp_path / "data")
    with pytest.raises(TrainError, match="multiples of 32"):
        fit(_model(), _options(data, tmp_path / "r", input_size=(60, 64)), CLASS_NAMES)
    with pytest.raises(TrainError, match="device 'tpu'"):
        fit(_model(), _options(data, tmp_path / "r", device="tpu"), CLASS_NAMES)
    with pytest.raises(TrainError, match="not .*data.yaml's names"):
        fit(_model(), _options(data, tmp_path / "r"), ["a", "b", "c", "d"])
    with pytest.raises(TrainError, match="nothing to resume"):
        fit(_model(), _options(data, tmp_path / "fresh", resume=True), CLASS_NAMES)
    if not torch.cuda.is_available():
        with pytest.raises(TrainError, match="CUDA is not available"):
            fit(_model(), _options(data, tmp_path / "r", device="cuda"), CLASS_NAMES)
