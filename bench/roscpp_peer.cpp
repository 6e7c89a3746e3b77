// roscpp_peer: a small real-roscpp node used by rostui's benchmarks and interop tests.
//
// Build (from the repository root):
//   g++ -O2 bench/roscpp_peer.cpp -o bench/_build/roscpp_peer -I/usr/include
//       -lroscpp -lrosconsole -lroscpp_serialization -lrostime -lxmlrpcpp
//       -lcpp_common -lboost_system
//
// Modes (argv[1]); the node is "roscpp_peer" made anonymous, and ros::init
// consumes remaps (from:=to, __name:=, ...) before the mode arguments are read:
//   talk TOPIC COUNT HZ      publish std_msgs/String "hello N" (N = 0..COUNT-1) at HZ once
//                            there is a subscriber, then keep running 1 s; exit 0
//   listen TOPIC COUNT       print each std_msgs/String's data on its own line (flushed);
//                            exit 0 after COUNT messages
//   serve SERVICE            serve std_srvs/SetBool: success=true, message="got true|false";
//                            run until SIGINT
//   call SERVICE             wait for the SetBool service (30 s at most), call it with
//                            data=true, print "success=<0|1> message=<text>"; exit 0, or 1
//                            when the service never came or the call failed
//   flood TOPIC SIZE SECONDS publish SIZE-byte std_msgs/String as fast as possible
//                            (queue 1000) once subscribed, for SECONDS
//   count TOPIC SECONDS      subscribe (tcp_nodelay), count messages and payload bytes
//                            received during SECONDS after the first message; print
//                            "count=N bytes=B seconds=S"
//   pong IN OUT              echo every std_msgs/String from IN to OUT (tcp_nodelay)
//   ping OUT IN N            N timed round trips after a warm-up; print "timing" when they
//                            start, then "n=N p50_us=X p99_us=Y mean_us=M min_us=A max_us=B cpu_us=C"
//                            (cpu_us: this process's CPU time per timed round trip)
//
// std_srvs/SetBool is declared below (wire traits written for this file) so the
// peer builds with libroscpp-dev and std_msgs alone, without libstd-srvs-dev.

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

// ---------------------------------------------------------------------------
// std_srvs/SetBool, declared here: request "bool data", response
// "bool success / string message".
namespace peer_srv {

struct SetBoolRequest {
  uint8_t data = 0;
};
struct SetBoolResponse {
  uint8_t success = 0;
  std::string message;
};
struct SetBool {
  typedef SetBoolRequest Request;
  typedef SetBoolResponse Response;
  Request request;
  Response response;
};

constexpr const char* kServiceMd5 = "09fb03525b03e7ea1fd3992bafd87e16";
constexpr const char* kServiceType = "std_srvs/SetBool";

}  // namespace peer_srv

namespace ros {
namespace message_traits {

template <> struct MD5Sum<peer_srv::SetBoolRequest> {
  static const char* value() { return "8b94c1b53db61fb6aed406028ad6332a"; }
  static const char* value(const peer_srv::SetBoolRequest&) { return value(); }
};
template <> struct DataType<peer_srv::SetBoolRequest> {
  static const char* value() { return "std_srvs/SetBoolRequest"; }
  static const char* value(const peer_srv::SetBoolRequest&) { return value(); }
};
template <> struct Definition<peer_srv::SetBoolRequest> {
  static const char* value() { return "bool data\n"; }
  static const char* value(const peer_srv::SetBoolRequest&) { return value(); }
};
template <> struct MD5Sum<peer_srv::SetBoolResponse> {
  static const char* value() { return "937c9679a518e3a18d831e57125ea522"; }
  static const char* value(const peer_srv::SetBoolResponse&) { return value(); }
};
template <> struct DataType<peer_srv::SetBoolResponse> {
  static const char* value() { return "std_srvs/SetBoolResponse"; }
  static const char* value(const peer_srv::SetBoolResponse&) { return value(); }
};
template <> struct Definition<peer_srv::SetBoolResponse> {
  static const char* value() { return "bool success\nstring message\n"; }
  static const char* value(const peer_srv::SetBoolResponse&) { return value(); }
};

}  // namespace message_traits

namespace serialization {

template <> struct Serializer<peer_srv::SetBoolRequest> {
  template <typename Stream, typename T> inline static void allInOne(Stream& stream, T m) {
    stream.next(m.data);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};
template <> struct Serializer<peer_srv::SetBoolResponse> {
  template <typename Stream, typename T> inline static void allInOne(Stream& stream, T m) {
    stream.next(m.success);
    stream.next(m.message);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

}  // namespace serialization

namespace service_traits {

#define PEER_SETBOOL_SERVICE_TRAITS(T)                                          \
  template <> struct MD5Sum<T> {                                                \
    static const char* value() { return peer_srv::kServiceMd5; }                \
    static const char* value(const T&) { return value(); }                     \
  };                                                                            \
  template <> struct DataType<T> {                                              \
    static const char* value() { return peer_srv::kServiceType; }               \
    static const char* value(const T&) { return value(); }                      \
  };

PEER_SETBOOL_SERVICE_TRAITS(peer_srv::SetBool)
PEER_SETBOOL_SERVICE_TRAITS(peer_srv::SetBoolRequest)
PEER_SETBOOL_SERVICE_TRAITS(peer_srv::SetBoolResponse)
#undef PEER_SETBOOL_SERVICE_TRAITS

}  // namespace service_traits
}  // namespace ros

// ---------------------------------------------------------------------------

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

int usage() {
  std::fprintf(stderr,
               "usage: roscpp_peer talk TOPIC COUNT HZ | listen TOPIC COUNT | serve SERVICE |\n"
               "       call SERVICE | flood TOPIC SIZE SECONDS | count TOPIC SECONDS |\n"
               "       pong IN OUT | ping OUT IN N\n");
  return 2;
}

// Spin callbacks until pred() is true or the node shuts down; false on shutdown/timeout.
template <typename Pred> bool spin_until(Pred pred, double timeout_s = -1.0) {
  auto t0 = Clock::now();
  while (ros::ok() && !pred()) {
    if (timeout_s >= 0 && seconds_since(t0) > timeout_s) return false;
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
  }
  return ros::ok();
}

int mode_talk(ros::NodeHandle& nh, const std::string& topic, long count, double hz) {
  ros::Publisher pub = nh.advertise<std_msgs::String>(topic, 1000);
  if (!spin_until([&] { return pub.getNumSubscribers() > 0; })) return 1;
  ros::Rate rate(hz);
  for (long i = 0; i < count && ros::ok(); ++i) {
    std_msgs::String msg;
    msg.data = "hello " + std::to_string(i);
    pub.publish(msg);
    ros::spinOnce();
    rate.sleep();
  }
  auto t0 = Clock::now();
  spin_until([&] { return seconds_since(t0) >= 1.0; });
  return 0;
}

int mode_listen(ros::NodeHandle& nh, const std::string& topic, long count) {
  long got = 0;
  ros::Subscriber sub = nh.subscribe<std_msgs::String>(
      topic, 1000,
      [&](const std_msgs::String::ConstPtr& msg) {
        if (got >= count) return;
        std::fwrite(msg->data.data(), 1, msg->data.size(), stdout);
        std::fputc('\n', stdout);
        std::fflush(stdout);
        ++got;
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  spin_until([&] { return got >= count; });
  return got >= count ? 0 : 1;
}

int mode_serve(ros::NodeHandle& nh, const std::string& service) {
  boost::function<bool(peer_srv::SetBoolRequest&, peer_srv::SetBoolResponse&)> handler =
      [](peer_srv::SetBoolRequest& req, peer_srv::SetBoolResponse& res) {
        res.success = 1;
        res.message = req.data ? "got true" : "got false";
        return true;
      };
  ros::ServiceServer srv = nh.advertiseService(service, handler);
  ros::spin();  // roscpp's SIGINT handler ends this
  return 0;
}

int mode_call(ros::NodeHandle& nh, const std::string& service) {
  std::string name = nh.resolveName(service);
  if (!ros::service::waitForService(name, ros::Duration(30.0))) {
    std::fprintf(stderr, "service %s did not appear\n", name.c_str());
    return 1;
  }
  peer_srv::SetBool srv;
  srv.request.data = 1;
  if (!ros::service::call(name, srv)) {
    std::fprintf(stderr, "call to %s failed\n", name.c_str());
    return 1;
  }
  std::printf("success=%d message=%s\n", srv.response.success ? 1 : 0, srv.response.message.c_str());
  std::fflush(stdout);
  return 0;
}

int mode_flood(ros::NodeHandle& nh, const std::string& topic, long size, double seconds) {
  ros::Publisher pub = nh.advertise<std_msgs::String>(topic, 1000);
  if (!spin_until([&] { return pub.getNumSubscribers() > 0; })) return 1;
  std_msgs::String msg;
  msg.data.assign(static_cast<size_t>(size), 'x');
  auto t0 = Clock::now();
  long sent = 0;
  while (ros::ok() && seconds_since(t0) < seconds) {
    pub.publish(msg);
    ++sent;
    if ((sent & 255) == 0) ros::spinOnce();
  }
  std::fprintf(stderr, "flood: published %ld messages\n", sent);
  return 0;
}

int mode_count(ros::NodeHandle& nh, const std::string& topic, double seconds) {
  long count = 0;
  long long bytes = 0;
  bool started = false;
  Clock::time_point t0;
  ros::Subscriber sub = nh.subscribe<std_msgs::String>(
      topic, 100000,
      [&](const std_msgs::String::ConstPtr& msg) {
        auto now = Clock::now();
        if (!started) {
          started = true;
          t0 = now;
        } else if (std::chrono::duration<double>(now - t0).count() > seconds) {
          return;
        }
        ++count;
        bytes += static_cast<long long>(msg->data.size());
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  if (!spin_until([&] { return started && seconds_since(t0) >= seconds; })) return 1;
  std::printf("count=%ld bytes=%lld seconds=%.3f\n", count, bytes, seconds_since(t0));
  std::fflush(stdout);
  return 0;
}

int mode_pong(ros::NodeHandle& nh, const std::string& in, const std::string& out) {
  ros::Publisher pub = nh.advertise<std_msgs::String>(out, 1000);
  ros::Subscriber sub = nh.subscribe<std_msgs::String>(
      in, 1000, [&](const std_msgs::String::ConstPtr& msg) { pub.publish(*msg); }, ros::VoidConstPtr(),
      ros::TransportHints().tcpNoDelay());
  ros::spin();
  return 0;
}

int mode_ping(ros::NodeHandle& nh, const std::string& out, const std::string& in, long n) {
  ros::Publisher pub = nh.advertise<std_msgs::String>(out, 1000);
  std::string last;
  long replies = 0;
  ros::Subscriber sub = nh.subscribe<std_msgs::String>(
      in, 1000,
      [&](const std_msgs::String::ConstPtr& msg) {
        last = msg->data;
        ++replies;
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  if (!spin_until([&] { return pub.getNumSubscribers() > 0 && sub.getNumPublishers() > 0; }, 30.0)) {
    std::fprintf(stderr, "ping: peers never connected\n");
    return 1;
  }
  std_msgs::String msg;
  // Until the echo path works end to end, resend every 100 ms.
  msg.data = "warmup";
  bool echoed = false;
  for (int i = 0; i < 300 && !echoed && ros::ok(); ++i) {
    pub.publish(msg);
    echoed = spin_until([&] { return last == "warmup"; }, 0.1);
  }
  if (!echoed) {
    std::fprintf(stderr, "ping: no echo\n");
    return 1;
  }
  long warm = std::max(100L, n / 10);
  std::vector<double> rtt;
  rtt.reserve(static_cast<size_t>(n));
  std::clock_t cpu0 = 0;
  for (long i = 0; i < warm + n && ros::ok(); ++i) {
    if (i == warm) {
      std::printf("timing\n");  // the timed round trips start
      std::fflush(stdout);
      cpu0 = std::clock();
    }
    msg.data = "ping " + std::to_string(i);
    auto t0 = Clock::now();
    pub.publish(msg);
    while (last != msg.data) {
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(1.0));
      if (!ros::ok() || seconds_since(t0) > 5.0) {
        std::fprintf(stderr, "ping: reply %ld lost\n", i);
        return 1;
      }
    }
    if (i >= warm) rtt.push_back(seconds_since(t0) * 1e6);
  }
  if (rtt.empty()) return 1;
  double cpu_us = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC * 1e6 / rtt.size();
  std::sort(rtt.begin(), rtt.end());
  double sum = 0;
  for (double x : rtt) sum += x;
  auto pct = [&](double p) { return rtt[std::min(rtt.size() - 1, static_cast<size_t>(p * rtt.size()))]; };
  std::printf("n=%zu p50_us=%.1f p99_us=%.1f mean_us=%.1f min_us=%.1f max_us=%.1f cpu_us=%.1f\n", rtt.size(),
              pct(0.50), pct(0.99), sum / rtt.size(), rtt.front(), rtt.back(), cpu_us);
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "roscpp_peer", ros::init_options::AnonymousName);
  // ros::init removed the remaps; argv now holds the mode and its arguments.
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return usage();
  const std::string mode = args[0];
  static const std::vector<std::pair<std::string, size_t>> arity = {
      {"talk", 3}, {"listen", 2}, {"serve", 1}, {"call", 1},
      {"flood", 3}, {"count", 2}, {"pong", 2}, {"ping", 3}};
  auto known = std::find_if(arity.begin(), arity.end(), [&](const auto& m) { return m.first == mode; });
  if (known == arity.end() || args.size() != known->second + 1) return usage();
  auto need = [&](size_t k) { return args.size() == k + 1; };
  ros::NodeHandle nh;
  try {
    if (mode == "talk" && need(3)) return mode_talk(nh, args[1], std::stol(args[2]), std::stod(args[3]));
    if (mode == "listen" && need(2)) return mode_listen(nh, args[1], std::stol(args[2]));
    if (mode == "serve" && need(1)) return mode_serve(nh, args[1]);
    if (mode == "call" && need(1)) return mode_call(nh, args[1]);
    if (mode == "flood" && need(3)) return mode_flood(nh, args[1], std::stol(args[2]), std::stod(args[3]));
    if (mode == "count" && need(2)) return mode_count(nh, args[1], std::stod(args[2]));
    if (mode == "pong" && need(2)) return mode_pong(nh, args[1], args[2]);
    if (mode == "ping" && need(3)) return mode_ping(nh, args[1], args[2], std::stol(args[3]));
  } catch (const std::exception& exc) {
    std::fprintf(stderr, "roscpp_peer: %s\n", exc.what());
    return 2;
  }
  return usage();
}
