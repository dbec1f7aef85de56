"""YOLOv8 detector (n/s) with the optional Gold-YOLO GD neck and ASF-YOLO fusion of seed 000 §2.1."""
