"""A latched rospy Publisher with a SubscribeListener that greets each subscriber alone.

rospy makes what ``peer_publish`` sends the latched message, so the newcomer then gets the greeting again.

Run by tests/test_rospy_peers.py under Debian's rospy and under rostui's; both must print the same and
send the same to `rostopic echo`.
"""

import rospy
from std_msgs.msg import String


class Greeter(rospy.SubscribeListener):
    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        print("subscribed", topic_name, flush=True)
        peer_publish(String("welcome"))

    def peer_unsubscribe(self, topic_name, num_peers):
        print("unsubscribed", topic_name, num_peers, flush=True)


rospy.init_node("latched_talker")
# queue_size 10: with 1, a loaded machine lets the latched copy replace the greeting before its queue thread
# sends it (both rospys queue per connection), and the subscriber hears one message, not two
pub = rospy.Publisher("latched", String, latch=True, subscriber_listener=Greeter(), queue_size=10)
pub.publish(String("last"))
print("ready", flush=True)
rospy.spin()
