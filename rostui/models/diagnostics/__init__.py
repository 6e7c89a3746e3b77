"""What the diagnostics app and ``rostui diagnostics --once`` know without a screen: statuses, their tree, the source."""
