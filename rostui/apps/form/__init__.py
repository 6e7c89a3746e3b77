"""The form app: `rostui publish` and `rostui call` (rqt_publisher and rqt_service_caller in the terminal)."""
