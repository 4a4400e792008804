// The mock robot and Nav2's DDS side in eProsima Fast DDS (rmw_fastrtps's DDS), for
// interop.py, which runs the scenario: it writes commands on stdin and reads events on
// stdout, one line each.
//
//   fastdds_peer DOMAIN covariance|stamped|tf [NAME=TOPIC]...
//
// NAME=TOPIC gives the DDS name, without `rt/` (or `rq/` and `rr/`), of the topic `map`,
// `pose`, `tf`, `tf_static`, `command`, `goal` or `status`, or of the action `action`
// (by default `map`, ..., `explore/command`, ..., `navigate_to_pose`): for a node in a
// namespace or with remapping rules. Below, the topics by their default names.
//
// in:  map W H RES V...           the map (V: -1, 0 or 100 per cell, row-major from the origin)
//      pose X Y                   the robot's pose in the map frame, as POSE says:
//                                 covariance (PoseWithCovarianceStamped, as slam_toolbox
//                                 and AMCL send it) or stamped (PoseStamped)
//      tf|tf_static EDGE...       with POSE tf: one TFMessage on /tf or (latched)
//                                 /tf_static, each EDGE `PARENT CHILD X Y YAW Z`
//      command TEXT               on /explore/command
//      goal_reply TOKEN 0|1       answer send_goal request TOKEN (accepted or not)
//      result_reply TOKEN STATUS  answer get_result request TOKEN with a GoalStatus
//      cancel_reply TOKEN         answer cancel_goal request TOKEN (nothing to cancel)
// out: goal X Y FRAME             from /explore/goal
//      status TEXT                from /explore/status
//      send_goal TOKEN UUID X Y   a NavigateToPose goal (UUID in hex)
//      get_result TOKEN UUID
//      cancel TOKEN
//
// Services follow rmw_fastrtps: a request's id is its sample identity (the client's
// writer and the sequence number), or, when the request names one, the related sample
// identity's writer (the client's reply reader) with the request's sequence number; the
// reply carries it as its related sample identity. Types come from ros2.idl through
// fastddsgen.

#include <sys/select.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/common/WriteParams.h>

#include "ros2PubSubTypes.h"

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SampleIdentity;
using eprosima::fastrtps::rtps::WriteParams;
namespace geo = geometry_msgs::msg::dds_;
namespace nav = nav2_msgs::action::dds_;

struct Peer {
    DomainParticipant* dp;
    Publisher* pub;
    Subscriber* sub;

    template <class PubSub>
    Topic* topic(const std::string& name) {
        TypeSupport t(new PubSub());
        t.register_type(dp);
        Topic* found = dynamic_cast<Topic*>(dp->lookup_topicdescription(name));
        return found ? found : dp->create_topic(name, t.get_type_name(), TOPIC_QOS_DEFAULT);
    }
    // Reliable, keep last 10; latched: transient local, keep last 1 (ROS 2's QoS of /map,
    // /tf_static and the node's status).
    template <class Qos>
    static Qos ros(Qos q, bool latched) {
        q.reliability().kind = RELIABLE_RELIABILITY_QOS;
        q.durability().kind = latched ? TRANSIENT_LOCAL_DURABILITY_QOS : VOLATILE_DURABILITY_QOS;
        q.history().kind = KEEP_LAST_HISTORY_QOS;
        q.history().depth = latched ? 1 : 10;
        return q;
    }
    template <class PubSub>
    DataWriter* writer(const std::string& name, bool latched = false) {
        return pub->create_datawriter(topic<PubSub>(name), ros(DATAWRITER_QOS_DEFAULT, latched));
    }
    template <class PubSub>
    DataReader* reader(const std::string& name, bool latched = false) {
        return sub->create_datareader(topic<PubSub>(name), ros(DATAREADER_QOS_DEFAULT, latched));
    }
};

static std::string hex(const std::array<uint8_t, 16>& b) {
    static const char* d = "0123456789abcdef";
    std::string s;
    for (uint8_t x : b) {
        s += d[x >> 4];
        s += d[x & 15];
    }
    return s;
}

static builtin_interfaces::msg::dds_::Time_ now() {
    builtin_interfaces::msg::dds_::Time_ t;
    timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    t.sec(static_cast<int32_t>(ts.tv_sec));
    t.nanosec(static_cast<uint32_t>(ts.tv_nsec));
    return t;
}

static geo::Pose_ pose_at(double x, double y) {
    geo::Pose_ p;
    p.position().x(x);
    p.position().y(y);
    p.orientation().w(1.0);
    return p;
}

static geo::TransformStamped_ edge(const std::string& parent, const std::string& child, double x,
                                   double y, double yaw, double z) {
    geo::TransformStamped_ t;
    t.header().stamp(now());
    t.header().frame_id(parent);
    t.child_frame_id(child);
    t.transform().translation().x(x);
    t.transform().translation().y(y);
    t.transform().translation().z(z);
    t.transform().rotation().z(std::sin(yaw / 2));
    t.transform().rotation().w(std::cos(yaw / 2));
    return t;
}

// The id a reply must carry, as rmw_fastrtps takes it from a request.
static SampleIdentity request_id(const SampleInfo& info) {
    SampleIdentity id = info.sample_identity;
    if (info.related_sample_identity.writer_guid() != eprosima::fastrtps::rtps::GUID_t::unknown()) {
        id.writer_guid() = info.related_sample_identity.writer_guid();
    }
    return id;
}

int main(int argc, char** argv) {
    const std::string pose = argc >= 3 ? argv[2] : "";
    std::map<std::string, std::string> name = {
        {"map", "map"},
        {"pose", "pose"},
        {"tf", "tf"},
        {"tf_static", "tf_static"},
        {"command", "explore/command"},
        {"goal", "explore/goal"},
        {"status", "explore/status"},
        {"action", "navigate_to_pose"},
    };
    bool ok = argc >= 3 && (pose == "covariance" || pose == "stamped" || pose == "tf");
    for (int i = 3; ok && i < argc; ++i) {
        const std::string arg = argv[i];
        const size_t eq = arg.find('=');
        ok = eq != std::string::npos && eq + 1 < arg.size() && name.count(arg.substr(0, eq)) > 0;
        if (ok) {
            name[arg.substr(0, eq)] = arg.substr(eq + 1);
        }
    }
    if (!ok) {
        std::cerr << "usage: fastdds_peer DOMAIN covariance|stamped|tf [NAME=TOPIC]...\n"
                     "  NAME: map, pose, tf, tf_static, command, goal, status or action\n";
        return 2;
    }
    Peer p;
    p.dp = DomainParticipantFactory::get_instance()->create_participant(
        std::stoi(argv[1]), PARTICIPANT_QOS_DEFAULT);
    if (!p.dp) {
        std::cerr << "fastdds_peer: cannot create a participant\n";
        return 1;
    }
    p.pub = p.dp->create_publisher(PUBLISHER_QOS_DEFAULT);
    p.sub = p.dp->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
    using namespace nav_msgs::msg::dds_;
    using namespace std_msgs::msg::dds_;
    DataWriter* map_w = p.writer<OccupancyGrid_PubSubType>("rt/" + name["map"], true);
    using tf2_msgs::msg::dds_::TFMessage_;
    using tf2_msgs::msg::dds_::TFMessage_PubSubType;
    const bool tf = pose == "tf";
    const std::string pose_topic = "rt/" + name["pose"];
    DataWriter* pose_w = pose == "stamped"      ? p.writer<geo::PoseStamped_PubSubType>(pose_topic)
                         : pose == "covariance" ? p.writer<geo::PoseWithCovarianceStamped_PubSubType>(pose_topic)
                                                : nullptr;
    DataWriter* tf_w = tf ? p.writer<TFMessage_PubSubType>("rt/" + name["tf"]) : nullptr;
    DataWriter* static_w =
        tf ? p.writer<TFMessage_PubSubType>("rt/" + name["tf_static"], true) : nullptr;
    if (tf ? !tf_w || !static_w : !pose_w) {
        std::cerr << "fastdds_peer: cannot create the pose writers\n";
        return 1;
    }
    DataWriter* cmd_w = p.writer<String_PubSubType>("rt/" + name["command"]);
    DataReader* goal_r = p.reader<geo::PoseStamped_PubSubType>("rt/" + name["goal"]);
    DataReader* status_r = p.reader<String_PubSubType>("rt/" + name["status"], true);
    const std::string base = name["action"] + "/_action/";
    DataReader* send_goal_r = p.reader<nav::NavigateToPose_SendGoal_Request_PubSubType>(
        "rq/" + base + "send_goalRequest");
    DataWriter* send_goal_w = p.writer<nav::NavigateToPose_SendGoal_Response_PubSubType>(
        "rr/" + base + "send_goalReply");
    DataReader* result_r = p.reader<nav::NavigateToPose_GetResult_Request_PubSubType>(
        "rq/" + base + "get_resultRequest");
    DataWriter* result_w = p.writer<nav::NavigateToPose_GetResult_Response_PubSubType>(
        "rr/" + base + "get_resultReply");
    DataReader* cancel_r = p.reader<action_msgs::srv::dds_::CancelGoal_Request_PubSubType>(
        "rq/" + base + "cancel_goalRequest");
    DataWriter* cancel_w = p.writer<action_msgs::srv::dds_::CancelGoal_Response_PubSubType>(
        "rr/" + base + "cancel_goalReply");
    if (!map_w || !cmd_w || !goal_r || !status_r || !send_goal_r || !send_goal_w ||
        !result_r || !result_w || !cancel_r || !cancel_w) {
        std::cerr << "fastdds_peer: cannot create the readers and writers\n";
        return 1;
    }

    std::map<long, SampleIdentity> pending;
    long next_token = 0;
    std::string line;
    std::string pending_input;
    bool open = true;
    while (open) {
        // Commands from interop.py, waiting at most 10 ms for one.
        fd_set fds;
        FD_ZERO(&fds);
        FD_SET(0, &fds);
        timeval tv{0, 10000};
        if (select(1, &fds, nullptr, nullptr, &tv) > 0) {
            char buf[65536];
            ssize_t n = read(0, buf, sizeof buf);
            if (n <= 0) {
                open = false;
            } else {
                pending_input.append(buf, static_cast<size_t>(n));
            }
        }
        size_t eol;
        while ((eol = pending_input.find('\n')) != std::string::npos) {
            std::istringstream in(pending_input.substr(0, eol));
            pending_input.erase(0, eol + 1);
            std::string what;
            in >> what;
            if (what == "map") {
                OccupancyGrid_ m;
                uint32_t w, h;
                float res;
                in >> w >> h >> res;
                m.header().stamp(now());
                m.header().frame_id("map");
                m.info().map_load_time(now());
                m.info().resolution(res);
                m.info().width(w);
                m.info().height(h);
                m.info().origin(pose_at(0.0, 0.0));
                m.data().resize(static_cast<size_t>(w) * h);
                for (auto& v : m.data()) {
                    int x;
                    in >> x;
                    v = static_cast<uint8_t>(static_cast<int8_t>(x));
                }
                map_w->write(&m);
            } else if (what == "pose") {
                double x, y;
                in >> x >> y;
                std_msgs::msg::dds_::Header_ header;
                header.stamp(now());
                header.frame_id("map");
                if (pose == "stamped") {
                    geo::PoseStamped_ ps;
                    ps.header(header);
                    ps.pose(pose_at(x, y));
                    pose_w->write(&ps);
                } else {
                    geo::PoseWithCovarianceStamped_ ps;
                    ps.header(header);
                    ps.pose().pose(pose_at(x, y));
                    ps.pose().covariance()[0] = ps.pose().covariance()[7] = 0.01;
                    ps.pose().covariance()[35] = 0.005;
                    pose_w->write(&ps);
                }
            } else if ((what == "tf" || what == "tf_static") && tf) {
                TFMessage_ m;
                std::string parent, child;
                double x, y, yaw, z;
                while (in >> parent >> child >> x >> y >> yaw >> z) {
                    m.transforms().push_back(edge(parent, child, x, y, yaw, z));
                }
                (what == "tf" ? tf_w : static_w)->write(&m);
            } else if (what == "command") {
                String_ s;
                std::string text;
                std::getline(in >> std::ws, text);
                s.data(text);
                cmd_w->write(&s);
            } else if (what == "goal_reply" || what == "result_reply" || what == "cancel_reply") {
                long token;
                in >> token;
                auto it = pending.find(token);
                if (it == pending.end()) {
                    continue;
                }
                WriteParams wp;
                wp.related_sample_identity(it->second);
                pending.erase(it);
                if (what == "goal_reply") {
                    int accepted;
                    in >> accepted;
                    nav::NavigateToPose_SendGoal_Response_ r;
                    r.accepted(accepted != 0);
                    r.stamp(now());
                    send_goal_w->write(&r, wp);
                } else if (what == "result_reply") {
                    int status;
                    in >> status;
                    nav::NavigateToPose_GetResult_Response_ r;
                    r.status(static_cast<uint8_t>(status));
                    result_w->write(&r, wp);
                } else {
                    action_msgs::srv::dds_::CancelGoal_Response_ r;
                    cancel_w->write(&r, wp);
                }
            }
        }
        // Events for interop.py.
        SampleInfo info;
        geo::PoseStamped_ g;
        while (goal_r->take_next_sample(&g, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) {
                std::printf("goal %.6f %.6f %s\n", g.pose().position().x(),
                            g.pose().position().y(), g.header().frame_id().c_str());
            }
        }
        String_ s;
        while (status_r->take_next_sample(&s, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) {
                std::printf("status %s\n", s.data().c_str());
            }
        }
        nav::NavigateToPose_SendGoal_Request_ sg;
        while (send_goal_r->take_next_sample(&sg, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) {
                pending[next_token] = request_id(info);
                const auto& pos = sg.goal().pose().pose().position();
                std::printf("send_goal %ld %s %.6f %.6f\n", next_token++,
                            hex(sg.goal_id().uuid()).c_str(), pos.x(), pos.y());
            }
        }
        nav::NavigateToPose_GetResult_Request_ gr;
        while (result_r->take_next_sample(&gr, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) {
                pending[next_token] = request_id(info);
                std::printf("get_result %ld %s\n", next_token++, hex(gr.goal_id().uuid()).c_str());
            }
        }
        action_msgs::srv::dds_::CancelGoal_Request_ cr;
        while (cancel_r->take_next_sample(&cr, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) {
                pending[next_token] = request_id(info);
                std::printf("cancel %ld\n", next_token++);
            }
        }
        std::fflush(stdout);
    }
    p.dp->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(p.dp);
    return 0;
}
