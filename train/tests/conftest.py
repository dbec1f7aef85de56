"""Puts train/ on sys.path so that ``import semchain_train`` works from any working directory, and runs
torch on one thread: the tensors here are tiny, and on a shared 2-core machine a second OpenMP thread
makes them many times slower."""

import sys
from pathlib import Path

import torch

TRAIN_DIR = Path(__file__).resolve().parents[1]
if str(TRAIN_DIR) not in sys.path:
    sys.path.insert(0, str(TRAIN_DIR))

torch.set_num_threads(1)
