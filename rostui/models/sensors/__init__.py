"""Screen-free models of `rostui view`: its node and topic types (source), and sensor messages (images, scans, ...)
decoded into arrays the views draw."""
