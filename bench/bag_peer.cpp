// bag_peer: the roscpp peers of bench_bag.py's recording benchmark.
//
//   bag_peer publish TOPIC SIZE RATE SECONDS QUEUE
//     Once a subscriber is connected (and 0.3 s more), publishes RATE std_msgs/String
//     messages per second for SECONDS, each SIZE bytes of data starting with its number
//     (8 digits). The message is kept as its wire bytes, so roscpp's serialisation is one
//     memcpy and the publisher's own cost stays far below any recorder's.
//     Publishing runs on schedule: a message that is due goes out at once,
//     and when the subscriber reads too slowly roscpp's per-subscriber queue of QUEUE
//     messages drops the oldest, as every ROS publisher does. Then it prints
//     {"sent": N, "seconds": S} and keeps its connections open (so queued messages
//     still go out) until SIGINT or until its subscriber leaves.
//
//   bag_peer count TOPIC
//     A recorder that records nothing: subscribes to std_msgs/String (queue 100000)
//     without deserialising it (roscpp has read the frame; the callback only counts),
//     counts the messages, and once none has come for 1 s after the first one prints
//     {"received": N} and exits. Receiving is all it does, so the highest rate it
//     holds is what the publisher, the kernel and one roscpp subscriber reach on this
//     machine: the most a roscpp recorder (rosbag record) could hold.
//
// Build (bench_bag.py does this itself):
//   g++ -O2 bench/bag_peer.cpp -o bench/_build/bag_peer -I/usr/include
//       -lroscpp -lrosconsole -lroscpp_serialization -lrostime -lxmlrpcpp -lcpp_common -lboost_system

#include <ros/ros.h>
#include <std_msgs/String.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

// A std_msgs/String whose wire bytes (string length and data) are laid out already: roscpp's
// serialisation of it is one memcpy into the buffer it sends, not a std::string walk.
struct WireString {
  std::vector<uint8_t> bytes;
};

// A std_msgs/String that a subscriber takes without deserialising: roscpp has read the
// frame into its buffer; the callback only counts.
struct CountedString {};

}  // namespace

namespace ros {
namespace message_traits {
// Each trait of both types answers what std_msgs/String's trait answers.
template <template <class> class Trait, class T>
struct AsString {
  static const char* value() { return Trait<std_msgs::String>::value(); }
  static const char* value(const T&) { return value(); }
};
template <> struct MD5Sum<WireString> : AsString<MD5Sum, WireString> {};
template <> struct MD5Sum<CountedString> : AsString<MD5Sum, CountedString> {};
template <> struct DataType<WireString> : AsString<DataType, WireString> {};
template <> struct DataType<CountedString> : AsString<DataType, CountedString> {};
template <> struct Definition<WireString> : AsString<Definition, WireString> {};
template <> struct Definition<CountedString> : AsString<Definition, CountedString> {};
}  // namespace message_traits

namespace serialization {
template <>
struct Serializer<WireString> {
  template <typename Stream>
  inline static void write(Stream& stream, const WireString& m) {
    std::memcpy(stream.advance(static_cast<uint32_t>(m.bytes.size())), m.bytes.data(), m.bytes.size());
  }
  inline static uint32_t serializedLength(const WireString& m) { return static_cast<uint32_t>(m.bytes.size()); }
};
template <>
struct Serializer<CountedString> {
  template <typename Stream>
  inline static void read(Stream&, CountedString&) {}
  inline static uint32_t serializedLength(const CountedString&) { return 0; }
};
}  // namespace serialization
}  // namespace ros

namespace {

using Clock = std::chrono::steady_clock;

int publish(const std::string& topic, long size, double rate, double seconds, int queue) {
  if (size < 8 || rate <= 0 || seconds <= 0 || queue < 1) {
    std::fprintf(stderr, "bag_peer publish: SIZE >= 8, RATE > 0, SECONDS > 0 and QUEUE >= 1 are needed\n");
    return 2;
  }
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::Publisher pub = nh.advertise<WireString>(topic, queue);

  const auto wait_start = Clock::now();
  while (ros::ok() && pub.getNumSubscribers() < 1) {
    if (Clock::now() - wait_start > std::chrono::seconds(60)) {
      std::fprintf(stderr, "bag_peer publish: no subscriber within 60 s\n");
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));

  WireString msg;
  msg.bytes.assign(static_cast<size_t>(size) + 4, 'x');
  const uint32_t length = static_cast<uint32_t>(size);
  std::memcpy(msg.bytes.data(), &length, 4);  // little-endian, as the wire wants on x86 and ARM
  const long count = static_cast<long>(rate * seconds);
  const auto start = Clock::now();
  char number[16];
  long sent = 0;
  for (; sent < count && ros::ok(); ++sent) {
    const auto due = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(sent / rate));
    std::this_thread::sleep_until(due);
    std::snprintf(number, sizeof number, "%08ld", sent);
    std::memcpy(msg.bytes.data() + 4, number, 8);
    pub.publish(msg);
  }
  const double took = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("{\"sent\": %ld, \"seconds\": %.6f}\n", sent, took);
  std::fflush(stdout);

  while (ros::ok() && pub.getNumSubscribers() > 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return 0;
}

int count(const std::string& topic) {
  ros::NodeHandle nh;
  std::atomic<long> received{0};
  std::atomic<Clock::rep> last{0};
  ros::Subscriber sub = nh.subscribe<CountedString>(
      topic, 100000, [&](const boost::shared_ptr<const CountedString>&) {
        ++received;
        last = Clock::now().time_since_epoch().count();
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  while (ros::ok()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const Clock::rep seen = last;
    if (seen && Clock::now().time_since_epoch().count() - seen > std::chrono::duration_cast<Clock::duration>(
                                                                      std::chrono::seconds(1)).count()) {
      break;
    }
  }
  std::printf("{\"received\": %ld}\n", received.load());
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bag_peer", ros::init_options::AnonymousName);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "publish" && argc == 7) {
    return publish(argv[2], std::atol(argv[3]), std::atof(argv[4]), std::atof(argv[5]), std::atoi(argv[6]));
  }
  if (mode == "count" && argc == 3) {
    return count(argv[2]);
  }
  std::fprintf(stderr, "usage: bag_peer publish TOPIC SIZE RATE SECONDS QUEUE | bag_peer count TOPIC\n");
  return 2;
}
