"""semchain_train: training, evaluation, pruning and export of semchain's YOLOv8-style detector.

Run as ``python3 -m semchain_train {train,val,prune,export} ...`` (see train/README.md).
Submodules are imported on demand so that ``--help`` and error reporting stay fast.
"""

__all__ = ["__version__"]

__version__ = "0.1.0"
