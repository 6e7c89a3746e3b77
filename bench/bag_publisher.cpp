// bag_publisher: the publisher of bench_bag.py's recording benchmark, a plain roscpp node.
//
//   bag_publisher TOPIC SIZE RATE SECONDS QUEUE
//
// Once a subscriber is connected (and 0.3 s more), publishes RATE std_msgs/String
// messages per second for SECONDS, each SIZE bytes of data starting with its number
// (8 digits). Publishing runs on schedule: a message that is due goes out at once,
// and when the subscriber reads too slowly roscpp's per-subscriber queue of QUEUE
// messages drops the oldest, as every ROS publisher does. Then it prints
// {"sent": N, "seconds": S} and keeps its connections open (so queued messages
// still go out) until SIGINT or until its subscriber leaves.
//
// Build (bench_bag.py does this itself):
//   g++ -O2 bench/bag_publisher.cpp -o bench/_build/bag_publisher -I/usr/include
//       -lroscpp -lrosconsole -lroscpp_serialization -lrostime -lxmlrpcpp -lcpp_common -lboost_system

#include <ros/ros.h>
#include <std_msgs/String.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  ros::init(argc, argv, "bag_publisher", ros::init_options::AnonymousName);
  if (argc != 6) {
    std::fprintf(stderr, "usage: bag_publisher TOPIC SIZE RATE SECONDS QUEUE\n");
    return 2;
  }
  const std::string topic = argv[1];
  const long size = std::atol(argv[2]);
  const double rate = std::atof(argv[3]);
  const double seconds = std::atof(argv[4]);
  const int queue = std::atoi(argv[5]);
  if (size < 8 || rate <= 0 || seconds <= 0 || queue < 1) {
    std::fprintf(stderr, "bag_publisher: SIZE >= 8, RATE > 0, SECONDS > 0 and QUEUE >= 1 are needed\n");
    return 2;
  }

  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::Publisher pub = nh.advertise<std_msgs::String>(topic, queue);

  using Clock = std::chrono::steady_clock;
  const auto wait_start = Clock::now();
  while (ros::ok() && pub.getNumSubscribers() < 1) {
    if (Clock::now() - wait_start > std::chrono::seconds(60)) {
      std::fprintf(stderr, "bag_publisher: no subscriber within 60 s\n");
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
