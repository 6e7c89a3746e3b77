"""tf's maths for scripts (``tf.transformations``) and tools: 4x4 homogeneous matrices, (x, y, z, w) quaternions."""
