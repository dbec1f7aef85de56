"""Puts train/ on sys.path so that ``import semchain_train`` works from any working directory."""

import sys
from pathlib import Path

TRAIN_DIR = Path(__file__).resolve().parents[1]
if str(TRAIN_DIR) not in sys.path:
    sys.path.insert(0, str(TRAIN_DIR))
