// bag_peer: the roscpp peers of bench_bag.py's recording benchmark.
//
//   bag_peer publish TOPIC SIZE RATE SECONDS QUEUE
//     Once a subscriber is connected (and 0.3 s more), publishes RATE std_msgs/String
//     messages per second for SECONDS, each SIZE bytes of data starting with its number
//     (8 digits). Publishing runs on schedule: a message that is due goes out at once,
//     and when the subscriber reads too slowly roscpp's per-subscriber queue of QUEUE
//     messages drops the oldest, as every ROS publisher does. Then it prints
//     {"sent": N, "seconds": S} and keeps its connections open (so queued messages
//     still go out) until SIGINT or until its subscriber leaves.
//
//   bag_peer count TOPIC
//     A recorder that records nothing: subscribes to std_msgs/String (queue 100000),
//     counts the messages, and once none has come for 1 s after the first one prints
//     {"received": N} and exits. Receiving is all it does, so the highest rate it
//     holds is what the publisher, the kernel and one roscpp subscriber reach on this
//     machine: the ceiling for every recorder.
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
#include <string>
#include <thread>

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
  ros::Publisher pub = nh.advertise<std_msgs::String>(topic, queue);

  const auto wait_start = Clock::now();
  while (ros::ok() && pub.getNumSubscribers() < 1) {
    if (Clock::now() - wait_start > std::chrono::seconds(60)) {
      std::fprintf(stderr, "bag_peer publish: no subscriber within 60 s\n");
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));

  std_msgs::String msg;
  msg.data.assign(static_cast<size_t>(size), 'x');
  const long count = static_cast<long>(rate * seconds);
  const auto start = Clock::now();
  char number[16];
  long sent = 0;
  for (; sent < count && ros::ok(); ++sent) {
    const auto due = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(sent / rate));
    std::this_thread::sleep_until(due);
    std::snprintf(number, sizeof number, "%08ld", sent);
    msg.data.replace(0, 8, number, 8);
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
  ros::Subscriber sub = nh.subscribe<std_msgs::String>(
      topic, 100000, [&](const std_msgs::String::ConstPtr&) {
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
