"""``rostui monitor``: every topic live in one table (rqt_topic, rostopic echo/hz/bw and rqt_plot in the terminal).

The data (rows, statistics, message trees, subscriptions, publishing) is in
:mod:`rostui.models.monitor`; the modules here only draw it.
"""
