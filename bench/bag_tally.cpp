// bag_tally: the subscriber of bench_bag_view.py's playback benchmark.
//
//   bag_tally RATE TOPIC:STAMP_OFFSET ...
//     One roscpp node subscribes to every TOPIC with md5sum and type "*" (it takes any type, as
//     rosbag record does) and a queue of 1000000, so it never drops what arrived. It does not
//     deserialise: each message's size and the header stamp found STAMP_OFFSET bytes into it
//     (4 for a message that starts with std_msgs/Header: after its seq) are kept with the arrival
//     time. Once nothing has come for 2 s after the first message it prints one JSON line:
//     messages and bytes received per topic, first and last arrival (steady clock, seconds), and
//     the lag behind the player's schedule: for message i, arrival_i - stamp_i / RATE, less the
//     smallest such value (the least late message sets the schedule's start), as p50/p99/max and
//     for the last message.
//
// Build (bench_bag_view.py does this itself):
//   g++ -O2 bench/bag_tally.cpp -o bench/_build/bag_tally -I/usr/include
//       -lroscpp -lrosconsole -lroscpp_serialization -lrostime -lxmlrpcpp -lcpp_common -lboost_system

#include <ros/ros.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace {

// What the subscriber keeps of a message: its size and its first 16 bytes (where the stamp is).
struct Frame {
  uint32_t size = 0;
  uint8_t head[16] = {};
};

}  // namespace

namespace ros {
namespace message_traits {
template <> struct MD5Sum<Frame> {
  static const char* value() { return "*"; }
  static const char* value(const Frame&) { return "*"; }
};
template <> struct DataType<Frame> {
  static const char* value() { return "*"; }
  static const char* value(const Frame&) { return "*"; }
};
template <> struct Definition<Frame> {
  static const char* value() { return ""; }
  static const char* value(const Frame&) { return ""; }
};
}  // namespace message_traits

namespace serialization {
template <>
struct Serializer<Frame> {
  template <typename Stream>
  inline static void read(Stream& stream, Frame& m) {
    m.size = stream.getLength();
    std::memcpy(m.head, stream.getData(), std::min<uint32_t>(m.size, sizeof(m.head)));
  }
  inline static uint32_t serializedLength(const Frame& m) { return m.size; }
};
}  // namespace serialization
}  // namespace ros

namespace {

using Clock = std::chrono::steady_clock;

struct Arrival {
  int64_t at_ns;
  int64_t stamp_ns;
};

struct Topic {
  std::string name;
  uint32_t stamp_offset = 4;
  long received = 0;
  long long bytes = 0;
};

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

double percentile(std::vector<int64_t>& v, double q) {
  if (v.empty()) return 0.0;
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(i), v.end());
  return static_cast<double>(v[i]) / 1e9;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bag_tally", ros::init_options::AnonymousName);
  if (argc < 3) {
    std::fprintf(stderr, "usage: bag_tally RATE TOPIC:STAMP_OFFSET ...\n");
    return 2;
  }
  const double rate = std::atof(argv[1]);
  std::vector<Topic> topics(static_cast<size_t>(argc - 2));
  for (int a = 2; a < argc; ++a) {
    std::string spec = argv[a];
    const size_t colon = spec.rfind(':');
    Topic& t = topics[static_cast<size_t>(a - 2)];
    t.name = spec.substr(0, colon);
    t.stamp_offset = colon == std::string::npos ? 4 : static_cast<uint32_t>(std::atoi(spec.c_str() + colon + 1));
  }
  std::mutex lock;
  std::vector<Arrival> arrivals;
  arrivals.reserve(1 << 20);
  std::atomic<int64_t> last{0};
  int64_t first = 0;
  ros::NodeHandle nh;
  std::vector<ros::Subscriber> subs;
  for (Topic& t : topics) {
    Topic* topic = &t;
    ros::SubscribeOptions opts;
    opts.template init<Frame>(t.name, 1000000, [topic, &lock, &arrivals, &last, &first](
                                                     const boost::shared_ptr<const Frame>& m) {
      const int64_t at = now_ns();
      uint32_t secs = 0, nsecs = 0;
      if (topic->stamp_offset <= sizeof(m->head) - 8) {
        std::memcpy(&secs, m->head + topic->stamp_offset, 4);
        std::memcpy(&nsecs, m->head + topic->stamp_offset + 4, 4);
      }
      std::lock_guard<std::mutex> guard(lock);
      ++topic->received;
      topic->bytes += m->size;
      arrivals.push_back({at, static_cast<int64_t>(secs) * 1000000000LL + nsecs});
      if (!first) first = at;
      last = at;
    });
    opts.transport_hints = ros::TransportHints().tcpNoDelay();
    subs.push_back(nh.subscribe(opts));
  }
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int64_t started = now_ns();
  while (ros::ok()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const int64_t seen = last;
    if (seen && now_ns() - seen > 2000000000LL) break;
    if (!seen && now_ns() - started > 600000000000LL) break;
  }
  spinner.stop();
  std::lock_guard<std::mutex> guard(lock);
  std::vector<int64_t> lags;
  lags.reserve(arrivals.size());
  int64_t least = 0;
  bool any = false;
  for (const Arrival& a : arrivals) {
    const int64_t v = a.at_ns - static_cast<int64_t>(static_cast<double>(a.stamp_ns) / rate);
    if (!any || v < least) least = v;
    any = true;
  }
  for (const Arrival& a : arrivals) {
    lags.push_back(a.at_ns - static_cast<int64_t>(static_cast<double>(a.stamp_ns) / rate) - least);
  }
  const double last_lag = lags.empty() ? 0.0 : static_cast<double>(lags.back()) / 1e9;
  std::printf("{\"topics\": {");
  for (size_t i = 0; i < topics.size(); ++i) {
    std::printf("%s\"%s\": [%ld, %lld]", i ? ", " : "", topics[i].name.c_str(), topics[i].received,
                topics[i].bytes);
  }
  std::printf("}, \"first_s\": %.6f, \"last_s\": %.6f, \"lag_p50_s\": %.6f, \"lag_p99_s\": %.6f, "
              "\"lag_max_s\": %.6f, \"lag_last_s\": %.6f}\n",
              static_cast<double>(first) / 1e9, static_cast<double>(last.load()) / 1e9, percentile(lags, 0.5),
              percentile(lags, 0.99), percentile(lags, 1.0), last_lag);
  std::fflush(stdout);
  return 0;
}
