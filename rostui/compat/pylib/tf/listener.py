"""tf.listener: tf's ``Transformer``, ``TransformerROS`` and ``TransformListener``, faces of a tf2_ros buffer.

Every frame argument loses one leading ``/`` (tf's ``/turtle1`` is tf2's ``turtle1``); lookups return
plain lists ``[x, y, z], [x, y, z, w]``; the exceptions are tf2's. ``waitForTransform`` needs a listener
(a thread that receives /tf): on a bare Transformer it raises, as tf does.
"""

from __future__ import annotations

from typing import Any

import numpy
import rospy
import tf2_ros

from rostui.core.msg import get_message_class

from . import transformations

__all__ = ["Transformer", "TransformerROS", "TransformListener", "strip_leading_slash"]

_NO_THREAD = "cannot wait for transform without a dedicated thread that listens to incoming TF messages"


def strip_leading_slash(s: str) -> str:
    """``s`` without one leading ``/``."""
    return s[1:] if s.startswith("/") else s


def _lists(msg: Any) -> tuple[list[float], list[float]]:
    t, r = msg.transform.translation, msg.transform.rotation
    return [t.x, t.y, t.z], [r.x, r.y, r.z, r.w]


class Transformer:
    """tf's transformer: a tf2 buffer (no ``~tf2_frames`` service) behind tf's method names."""

    def __init__(self, interpolate: bool = True, cache_time: Any = None) -> None:
        self._buffer = tf2_ros.Buffer(cache_time, debug=False)
        self._using_dedicated_thread = False

    def allFramesAsDot(self, current_time: Any = None) -> str:  # noqa: N802 (tf's names, here and below)
        """The tree as a Graphviz digraph."""
        return self._buffer._allFramesAsDot(current_time) if current_time else self._buffer._allFramesAsDot()

    def allFramesAsString(self) -> str:  # noqa: N802
        """``Frame C exists with parent P.`` lines."""
        return str(self._buffer.all_frames_as_string())

    def setTransform(self, transform: Any, authority: str = "default_authority") -> None:  # noqa: N802
        """Add a ``TransformStamped``."""
        self._buffer.set_transform(transform, authority)

    def canTransform(self, target_frame: str, source_frame: str, time: Any) -> bool:  # noqa: N802
        """Whether :meth:`lookupTransform` would answer now."""
        return bool(self._buffer.can_transform(strip_leading_slash(target_frame), strip_leading_slash(source_frame),
                                               time))

    def canTransformFull(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,  # noqa: N802
                         fixed_frame: str) -> bool:
        """Whether :meth:`lookupTransformFull` would answer now."""
        return bool(self._buffer.can_transform_full(strip_leading_slash(target_frame), target_time,
                                                    strip_leading_slash(source_frame), source_time,
                                                    strip_leading_slash(fixed_frame)))

    def _waited(self, answer: tuple[Any, str], target_frame: str, source_frame: str) -> None:
        ok, why = answer
        if not ok:
            raise tf2_ros.TransformException(why or f'no such transformation: "{source_frame}" -> "{target_frame}"')

    def waitForTransform(self, target_frame: str, source_frame: str, time: Any, timeout: Any,  # noqa: N802
                         polling_sleep_duration: Any = None) -> None:
        """Wait up to ``timeout`` until the transform is known; TransformException with tf2's reason if it is not."""
        if not self._using_dedicated_thread:
            raise tf2_ros.TransformException(_NO_THREAD)
        self._waited(self._buffer.can_transform(strip_leading_slash(target_frame), strip_leading_slash(source_frame),
                                                time, timeout, return_debug_tuple=True), target_frame, source_frame)

    def waitForTransformFull(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,  # noqa: N802
                             fixed_frame: str, timeout: Any, polling_sleep_duration: Any = None) -> None:
        """:meth:`waitForTransform` for the advanced lookup."""
        if not self._using_dedicated_thread:
            raise tf2_ros.TransformException(_NO_THREAD)
        self._waited(self._buffer.can_transform_full(
            strip_leading_slash(target_frame), target_time, strip_leading_slash(source_frame), source_time,
            strip_leading_slash(fixed_frame), timeout, return_debug_tuple=True), target_frame, source_frame)

    def chain(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
              fixed_frame: str) -> list[str]:
        """The frames between ``source_frame`` and ``target_frame`` through ``fixed_frame``."""
        return list(self._buffer._chain(target_frame, target_time, source_frame, source_time, fixed_frame))

    def clear(self) -> None:
        """Forget every transform."""
        self._buffer.clear()

    def frameExists(self, frame_id: str) -> bool:  # noqa: N802
        """Whether ``frame_id`` is a frame with a parent (tf's old meaning)."""
        return frame_id in self.getFrameStrings()

    def getFrameStrings(self) -> list[str]:  # noqa: N802
        """Every frame that has a parent, in the order tf2 lists them."""
        return [line.split(":")[0] for line in self._buffer.all_frames_as_yaml().splitlines()
                if line and not line.startswith(" ")]

    def getLatestCommonTime(self, source_frame: str, dest_frame: str) -> Any:  # noqa: N802
        """The newest time both frames' chain has data for."""
        return self._buffer.get_latest_common_time(strip_leading_slash(source_frame), strip_leading_slash(dest_frame))

    def lookupTransform(self, target_frame: str, source_frame: str, time: Any) -> tuple[list[float], list[float]]:  # noqa: N802
        """``([x, y, z], [x, y, z, w])``: the pose of ``source_frame`` in ``target_frame`` at ``time``."""
        return _lists(self._buffer.lookup_transform(strip_leading_slash(target_frame), strip_leading_slash(source_frame),
                                                    time))

    def lookupTransformFull(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,  # noqa: N802
                            fixed_frame: str) -> tuple[list[float], list[float]]:
        """:meth:`lookupTransform` between two times, through ``fixed_frame``."""
        return _lists(self._buffer.lookup_transform_full(strip_leading_slash(target_frame), target_time,
                                                         strip_leading_slash(source_frame), source_time,
                                                         strip_leading_slash(fixed_frame)))

    def lookupTwist(self, tracking_frame: str, observation_frame: str, time: Any, averaging_interval: Any) -> Any:  # noqa: N802
        """Linear and angular velocity of ``tracking_frame`` seen from ``observation_frame``."""
        return self.lookupTwistFull(tracking_frame, observation_frame, observation_frame, (0, 0, 0), tracking_frame,
                                    time, averaging_interval)

    def lookupTwistFull(self, tracking_frame: str, observation_frame: str, reference_frame: str,  # noqa: N802
                        ref_point: Any, reference_point_frame: str, time: Any,
                        averaging_interval: Any) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """Velocity of ``tracking_frame`` from ``observation_frame``, over ``averaging_interval`` around ``time``,
        expressed in ``reference_frame`` at a reference point (tf's finite-difference estimate)."""
        latest = self.getLatestCommonTime(observation_frame, tracking_frame)
        target_time = time or latest
        end = min(target_time + rospy.Duration(0.5 * averaging_interval.to_sec()), latest)
        start = max(rospy.Time(0.0001) + averaging_interval, end) - averaging_interval
        dt = (end - start).to_sec()
        start_tr, start_rt = self.lookupTransform(observation_frame, tracking_frame, start)
        end_tr, end_rt = self.lookupTransform(observation_frame, tracking_frame, end)
        turn = numpy.dot(numpy.linalg.inv(transformations.quaternion_matrix(start_rt)),
                         transformations.quaternion_matrix(end_rt))
        angle, axis, _ = transformations.rotation_from_matrix(turn)
        linear = numpy.array([(e - s) / dt for s, e in zip(start_tr, end_tr)])
        angular = numpy.array([axis[i] * angle / dt for i in range(3)])
        ref_tr, ref_rt = self.lookupTransform(reference_frame, tracking_frame, target_time)
        into_ref = transformations.quaternion_matrix(ref_rt)[:3, :3]
        rot = numpy.dot(into_ref, angular)
        vel = numpy.dot(into_ref, linear) + numpy.cross(ref_tr, rot)
        origin = numpy.array((ref_tr[0], ref_tr[1], ref_tr[2], 1.0))
        point_tr, point_rt = self.lookupTransform(reference_frame, reference_point_frame, target_time)
        moved = numpy.dot(numpy.dot(transformations.translation_matrix(point_tr),
                                    transformations.quaternion_matrix(point_rt)), origin)
        vel = vel + numpy.dot(rot, (moved - origin)[:3])
        return (vel[0], vel[1], vel[2]), (rot[0], rot[1], rot[2])

    def setUsingDedicatedThread(self, value: bool) -> None:  # noqa: N802
        """Say whether a thread feeds this transformer (a listener), which :meth:`waitForTransform` needs."""
        self._using_dedicated_thread = value

    def getTFPrefix(self) -> str:  # noqa: N802
        """The tf prefix: always empty since tf2."""
        return ""


def _msg(type_name: str) -> Any:
    return get_message_class(type_name)


class TransformerROS(Transformer):
    """A :class:`Transformer` that also moves stamped geometry messages and point clouds into a frame."""

    def asMatrix(self, target_frame: str, hdr: Any) -> Any:  # noqa: N802 (tf's names, here and below)
        """The 4x4 matrix from ``hdr.frame_id`` to ``target_frame`` at ``hdr.stamp``."""
        translation, rotation = self.lookupTransform(target_frame, hdr.frame_id, hdr.stamp)
        return self.fromTranslationRotation(translation, rotation)

    def fromTranslationRotation(self, translation: Any, rotation: Any) -> Any:  # noqa: N802
        """The 4x4 matrix of a translation and an (x, y, z, w) quaternion."""
        return numpy.dot(transformations.translation_matrix(translation), transformations.quaternion_matrix(rotation))

    @staticmethod
    def _moved(mat44: Any, x: float, y: float, z: float) -> tuple[float, ...]:
        return tuple(numpy.dot(mat44, numpy.array([x, y, z, 1.0])))[:3]

    @staticmethod
    def _stamped(type_name: str, header: Any, target_frame: str) -> Any:
        r = _msg(type_name)()
        r.header.stamp = header.stamp
        r.header.frame_id = target_frame
        return r

    def transformPoint(self, target_frame: str, ps: Any) -> Any:  # noqa: N802
        """A new ``PointStamped`` in ``target_frame`` (stamped as the input)."""
        mat44 = self.asMatrix(target_frame, ps.header)
        r = self._stamped("geometry_msgs/PointStamped", ps.header, target_frame)
        r.point = _msg("geometry_msgs/Point")(*self._moved(mat44, ps.point.x, ps.point.y, ps.point.z))
        return r

    def transformVector3(self, target_frame: str, v3s: Any) -> Any:  # noqa: N802
        """A new ``Vector3Stamped`` in ``target_frame``: turned, not moved."""
        mat44 = self.asMatrix(target_frame, v3s.header)
        mat44[0, 3] = mat44[1, 3] = mat44[2, 3] = 0.0
        r = self._stamped("geometry_msgs/Vector3Stamped", v3s.header, target_frame)
        r.vector = _msg("geometry_msgs/Vector3")(*self._moved(mat44, v3s.vector.x, v3s.vector.y, v3s.vector.z))
        return r

    def transformQuaternion(self, target_frame: str, ps: Any) -> Any:  # noqa: N802
        """A new ``QuaternionStamped`` in ``target_frame``."""
        mat44 = self.asMatrix(target_frame, ps.header)
        q = ps.quaternion
        turned = numpy.dot(mat44, transformations.quaternion_matrix((q.x, q.y, q.z, q.w)))
        r = self._stamped("geometry_msgs/QuaternionStamped", ps.header, target_frame)
        r.quaternion = _msg("geometry_msgs/Quaternion")(*tuple(transformations.quaternion_from_matrix(turned)))
        return r

    def transformPose(self, target_frame: str, ps: Any) -> Any:  # noqa: N802
        """A new ``PoseStamped`` in ``target_frame``."""
        mat44 = self.asMatrix(target_frame, ps.header)
        p, q = ps.pose.position, ps.pose.orientation
        pose44 = numpy.dot(transformations.translation_matrix((p.x, p.y, p.z)),
                           transformations.quaternion_matrix((q.x, q.y, q.z, q.w)))
        moved = numpy.dot(mat44, pose44)
        r = self._stamped("geometry_msgs/PoseStamped", ps.header, target_frame)
        r.pose = _msg("geometry_msgs/Pose")(
            _msg("geometry_msgs/Point")(*tuple(transformations.translation_from_matrix(moved))[:3]),
            _msg("geometry_msgs/Quaternion")(*tuple(transformations.quaternion_from_matrix(moved))))
        return r

    def transformPointCloud(self, target_frame: str, point_cloud: Any) -> Any:  # noqa: N802
        """A new ``sensor_msgs/PointCloud`` in ``target_frame``, its channels kept."""
        r = self._stamped("sensor_msgs/PointCloud", point_cloud.header, target_frame)
        r.channels = point_cloud.channels
        mat44 = self.asMatrix(target_frame, point_cloud.header)
        point = _msg("geometry_msgs/Point")
        r.points = [point(*self._moved(mat44, p.x, p.y, p.z)) for p in point_cloud.points]
        return r


class TransformListener(TransformerROS):
    """A :class:`TransformerROS` fed from /tf and /tf_static by a tf2_ros listener."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        TransformerROS.__init__(self, *args, **kwargs)
        self._listener = tf2_ros.TransformListener(self._buffer)
        self.setUsingDedicatedThread(True)
