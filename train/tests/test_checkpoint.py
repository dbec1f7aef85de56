from pathlib import Path

import pytest
import torch

from semchain_train.checkpoint import Checkpoint, load_checkpoint, save_checkpoint
from stand_in_detector import StandInConfig, StandInDetector


def _model(seed: int) -> StandInDetector:
    torch.manual_seed(seed)
    return StandInDetector(StandInConfig(classes=3))


def test_round_trip_keeps_weights_names_epoch_and_config(tmp_path: Path) -> None:
    model = _model(0)
    path = save_checkpoint(tmp_path / "a.pt", model, names=["a", "b", "c"], epoch=4, best_fitness=0.5)
    loaded = load_checkpoint(path)
    assert isinstance(loaded, Checkpoint)
    assert loaded.names == ["a", "b", "c"] and loaded.epoch == 4
    assert loaded.raw["best_fitness"] == 0.5 and loaded.raw["config"].classes == 3
    assert not loaded.model.training
    x = torch.rand(1, 3, 64, 64)
    model.eval()
    for expected, got in zip(model(x), loaded.model(x)):
        assert torch.equal(expected, got)


def test_ema_weights_are_loaded_when_present(tmp_path: Path) -> None:
    model, ema = _model(0), _model(1)
    save_checkpoint(tmp_path / "b.pt", model, names=["a", "b", "c"], epoch=0, ema=ema)
    loaded = load_checkpoint(tmp_path / "b.pt")
    assert torch.equal(loaded.model.heads[0][-1].weight, ema.heads[0][-1].weight)
    assert not torch.equal(loaded.model.heads[0][-1].weight, model.heads[0][-1].weight)
    assert torch.equal(loaded.raw["model"].heads[0][-1].weight, model.heads[0][-1].weight)


def test_saved_copy_is_float32_and_leaves_the_live_model_alone(tmp_path: Path) -> None:
    model = _model(0).double()
    save_checkpoint(tmp_path / "c.pt", model, names=["a", "b", "c"], epoch=0)
    assert next(model.parameters()).dtype == torch.float64
    loaded = load_checkpoint(tmp_path / "c.pt")
    assert all(p.dtype == torch.float32 for p in loaded.model.parameters())


def test_pruned_shapes_survive(tmp_path: Path) -> None:
    model = _model(0)
    model.heads[0][0][0] = torch.nn.Conv2d(16, 5, 1, bias=False)  # a layer with fewer channels, as pruning leaves
    model.heads[0][0][1] = torch.nn.BatchNorm2d(5)
    model.heads[0][1] = torch.nn.Conv2d(5, 67, 1)
    save_checkpoint(tmp_path / "p.pt", model, names=["a", "b", "c"], epoch=0)
    loaded = load_checkpoint(tmp_path / "p.pt")
    assert loaded.model.heads[0][1].weight.shape == (67, 5, 1, 1)
    assert loaded.model(torch.rand(1, 3, 64, 64))[0].shape == (1, 67, 8, 8)


def test_write_is_atomic_no_temporary_left_and_overwrite_works(tmp_path: Path) -> None:
    save_checkpoint(tmp_path / "d.pt", _model(0), names=["x"], epoch=0)
    save_checkpoint(tmp_path / "d.pt", _model(1), names=["x"], epoch=1)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.pt"]
    assert load_checkpoint(tmp_path / "d.pt").epoch == 1


def test_missing_file_is_a_clear_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="nope.pt"):
        load_checkpoint(tmp_path / "nope.pt")


@pytest.mark.parametrize("content", [b"", b"garbage bytes, not a zip", b"PK\x03\x04truncated"])
def test_corrupt_file_is_a_value_error_naming_the_path(tmp_path: Path, content: bytes) -> None:
    path = tmp_path / "bad.pt"
    path.write_bytes(content)
    with pytest.raises(ValueError, match="bad.pt"):
        load_checkpoint(path)


def test_foreign_torch_file_is_refused(tmp_path: Path) -> None:
    torch.save({"state_dict": {}}, tmp_path / "foreign.pt")
    with pytest.raises(ValueError, match="not a semchain_train checkpoint"):
        load_checkpoint(tmp_path / "foreign.pt")
