"""What ``rostui console`` knows without a screen: the bounded store of log rows, its filters, the live source."""
