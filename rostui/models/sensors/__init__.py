"""Screen-free decoding of sensor messages (images, scans, ...) into arrays the views draw."""
