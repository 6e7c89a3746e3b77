"""tf as the apps see it, without a screen: the live source fed from /tf and /tf_static, the tree's rows and
tf echo's lines. The maths and the buffer are tools' (:mod:`rostui.tools.tf`), shared with the CLI and the
tf/tf2_ros modules scripts import."""
