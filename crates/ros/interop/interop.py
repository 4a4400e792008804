"""frontier-ros against other vendors' DDS: a mock robot and Nav2 in Eclipse Cyclone DDS
(rmw_cyclonedds_cpp's DDS, through its Python binding) or in eProsima Fast DDS
(rmw_fastrtps's, the default RMW, through `fastdds_peer`), speaking to the node as ROS 2
nodes on that RMW do.

The node is built on RustDDS, and its own tests talk to it from RustDDS. Here the other
side is another vendor's DDS, with ROS 2's conventions written out by hand: topic names
`rt/...`, type names `pkg::msg::dds_::Type_`, plain CDR (XCDR1, what every ROS 2 RMW sends;
Cyclone would default to XCDR2 for these types), the map reliable and transient local. The
mock publishes a map and a pose (PoseWithCovarianceStamped with Nav2, PoseStamped in
publish-only mode, or with `--pose tf` as TF: map → odom → base_footprint on `/tf`,
base_footprint → base_link on `/tf_static`), moves the robot to each goal and reveals the true map there, pauses
and resumes the node through `/explore/command`, and checks that the node ends with
`done: explored` and every free cell known.

`--mode action`: the mock is also Nav2's `NavigateToPose` action server (services
`rq/navigate_to_pose/_action/send_goalRequest` and `rr/.../send_goalReply`, get_result,
cancel_goal), carried as that vendor's RMW carries services: Cyclone's with the client's
16-byte request id at the head of each request, repeated in the reply; Fast DDS's in the
samples' identities. It aborts the first goal, which must never come again; the node,
with `return_to_init`, ends by driving back to the start. `--nav2
humble` serves Humble's empty result instead of Jazzy's error code and message. The node runs
with `RMW_IMPLEMENTATION` set as beside such a Nav2 and its default `service_mapping:
auto`. `--mode publish-only`: the node only publishes goals and the mock follows them;
Nav2 must get nothing.

`--namespaced`: the node runs as a launch file's `Node(namespace="robot1", ...)` with
remapping rules (ROBOT1_ARGS), and the mock uses the names rcl gives them: the map on
`rt/shared_map`, the pose on `rt/robot1/amcl_pose` (or TF on `rt/robot1/tf` and
`rt/robot1/tf_static`), Nav2 at `rq/robot1/navigate_to_pose/_action/send_goalRequest` and
so on, the status and commands on `rt/robot1/explore/...`. In every run the node's DDS
readers and writers, as discovery announces them, must be on exactly the names expected,
and besides only on ROS 2's global topics and under its own name (parameter services):
none is left on an un-namespaced name.

Run by `scripts/ros-interop.sh`, which installs what it needs.
"""

import argparse
import math
import os
import subprocess
import sys
import time
from dataclasses import dataclass

from cyclonedds.builtin import (
    BuiltinDataReader,
    BuiltinTopicDcpsPublication,
    BuiltinTopicDcpsSubscription,
    DcpsEndpoint,
)
from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, float32, float64, int8, int32, sequence, uint8, uint16, uint32
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration


# Cyclone DDS: the ROS 2 (Jazzy) messages as the binding's IDL types (Fast DDS: ros2.idl).
@dataclass
class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: int32
    nanosec: uint32


@dataclass
class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time
    frame_id: str


@dataclass
class Point(IdlStruct, typename="geometry_msgs::msg::dds_::Point_"):
    x: float64
    y: float64
    z: float64


@dataclass
class Quaternion(IdlStruct, typename="geometry_msgs::msg::dds_::Quaternion_"):
    x: float64
    y: float64
    z: float64
    w: float64


@dataclass
class Pose(IdlStruct, typename="geometry_msgs::msg::dds_::Pose_"):
    position: Point
    orientation: Quaternion


@dataclass
class PoseStamped(IdlStruct, typename="geometry_msgs::msg::dds_::PoseStamped_"):
    header: Header
    pose: Pose


@dataclass
class PoseWithCovariance(IdlStruct, typename="geometry_msgs::msg::dds_::PoseWithCovariance_"):
    pose: Pose
    covariance: array[float64, 36]


@dataclass
class PoseWithCovarianceStamped(IdlStruct, typename="geometry_msgs::msg::dds_::PoseWithCovarianceStamped_"):
    header: Header
    pose: PoseWithCovariance


@dataclass
class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: float64
    y: float64
    z: float64


@dataclass
class Transform(IdlStruct, typename="geometry_msgs::msg::dds_::Transform_"):
    translation: Vector3
    rotation: Quaternion


@dataclass
class TransformStamped(IdlStruct, typename="geometry_msgs::msg::dds_::TransformStamped_"):
    header: Header
    child_frame_id: str
    transform: Transform


@dataclass
class TFMessage(IdlStruct, typename="tf2_msgs::msg::dds_::TFMessage_"):
    transforms: sequence[TransformStamped]


@dataclass
class MapMetaData(IdlStruct, typename="nav_msgs::msg::dds_::MapMetaData_"):
    map_load_time: Time
    resolution: float32
    width: uint32
    height: uint32
    origin: Pose


@dataclass
class OccupancyGrid(IdlStruct, typename="nav_msgs::msg::dds_::OccupancyGrid_"):
    header: Header
    info: MapMetaData
    data: sequence[int8]


@dataclass
class String(IdlStruct, typename="std_msgs::msg::dds_::String_"):
    data: str


@dataclass
class UUID(IdlStruct, typename="unique_identifier_msgs::msg::dds_::UUID_"):
    uuid: array[uint8, 16]


@dataclass
class NavGoal(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_Goal_"):
    pose: PoseStamped
    behavior_tree: str


@dataclass
class NavResult(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_Result_"):
    error_code: uint16
    error_msg: str


# rmw_cyclonedds_cpp's services: the request id (the client's id and a sequence number,
# 16 bytes) heads each request, and the reply repeats it.
@dataclass
class SendGoalRequest(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_SendGoal_Request_"):
    request_id: array[uint8, 16]
    goal_id: UUID
    goal: NavGoal


@dataclass
class SendGoalReply(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_SendGoal_Response_"):
    request_id: array[uint8, 16]
    accepted: bool
    stamp: Time


@dataclass
class GetResultRequest(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_GetResult_Request_"):
    request_id: array[uint8, 16]
    goal_id: UUID


@dataclass
class GetResultReply(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_GetResult_Response_"):
    request_id: array[uint8, 16]
    status: int8
    result: NavResult


@dataclass
class HumbleResult(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_Result_"):
    # Humble's result is std_msgs/Empty; an empty DDS struct holds this one byte.
    structure_needs_at_least_one_member: uint8


@dataclass
class HumbleGetResultReply(IdlStruct, typename="nav2_msgs::action::dds_::NavigateToPose_GetResult_Response_"):
    request_id: array[uint8, 16]
    status: int8
    result: HumbleResult


@dataclass
class GoalInfo(IdlStruct, typename="action_msgs::msg::dds_::GoalInfo_"):
    goal_id: UUID
    stamp: Time


@dataclass
class CancelRequest(IdlStruct, typename="action_msgs::srv::dds_::CancelGoal_Request_"):
    request_id: array[uint8, 16]
    goal_info: GoalInfo


@dataclass
class CancelReply(IdlStruct, typename="action_msgs::srv::dds_::CancelGoal_Response_"):
    request_id: array[uint8, 16]
    return_code: int8
    goals_canceling: sequence[GoalInfo]


# action_msgs/GoalStatus
SUCCEEDED, ABORTED = 4, 6


# Two floors of rooms joined by doors, 0.5 m cells (the node's loopback test's map).
ROOMS = """\
################
#......#.......#
#......#.......#
#..............#
#......#.......#
####.#######.###
#..............#
#..............#
################
"""
RES = 0.5
RANGE_M = 3.0
START = (2, 2)


class World:
    """The true map, what the robot has seen of it, and a line-of-sight sensor."""

    def __init__(self):
        lines = ROOMS.splitlines()
        self.h, self.w = len(lines), len(lines[0])
        # Row y of the grid is line h − 1 − y of the drawing (the map's origin is its
        # lower-left corner).
        self.free = [[lines[self.h - 1 - y][x] == "." for x in range(self.w)] for y in range(self.h)]
        self.known = [[False] * self.w for _ in range(self.h)]

    def sense(self, cx, cy):
        r = RANGE_M / RES
        for y in range(self.h):
            for x in range(self.w):
                if (x - cx) ** 2 + (y - cy) ** 2 <= r * r and self.visible(cx, cy, x, y):
                    self.known[y][x] = True

    def visible(self, x0, y0, x1, y1):
        # Every cell the segment between the centres passes, but the target, is free.
        n = max(abs(x1 - x0), abs(y1 - y0)) * 8
        for i in range(1, n):
            t = i / n
            x, y = math.floor(x0 + 0.5 + t * (x1 - x0)), math.floor(y0 + 0.5 + t * (y1 - y0))
            if (x, y) != (x1, y1) and not self.free[y][x]:
                return False
        return True

    def grid(self):
        data = []
        for y in range(self.h):
            for x in range(self.w):
                data.append(-1 if not self.known[y][x] else (0 if self.free[y][x] else 100))
        return data

    def unknown_free(self):
        return sum(
            1 for y in range(self.h) for x in range(self.w) if self.free[y][x] and not self.known[y][x]
        )


def stamp():
    t = time.time()
    return Time(sec=int(t), nanosec=int((t % 1) * 1e9))


# With `--pose tf`, the transforms as (parent, child, x, y, yaw, z), for either peer: the
# base link above the footprint (/tf_static), and (/tf) the odometry frame's fixed place
# on the map with the footprint in it, following the robot.
MAP_TO_ODOM = (1.0, 0.5, 0.3)
STATIC_EDGES = [("base_footprint", "base_link", 0.0, 0.0, 0.0, 0.1)]


def tf_edges(x, y):
    """/tf for the robot at map pose (x, y, 0): map → odom, and the footprint in the
    odometry frame, odom⁻¹ ∘ pose."""
    tx, ty, th = MAP_TO_ODOM
    dx, dy = x - tx, y - ty
    base = (math.cos(th) * dx + math.sin(th) * dy, -math.sin(th) * dx + math.cos(th) * dy, -th)
    return [("map", "odom", tx, ty, th, 0.0), ("odom", "base_footprint", *base, 0.0)]


def transform(parent, child, x, y, yaw, z=0.0):
    q = Quaternion(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
    return TransformStamped(Header(stamp(), parent), child, Transform(Vector3(x, y, z), q))


# The node's names as DDS names (without `rt/`, `rq/`, `rr/`), as rcl resolves them: with
# no namespace and no remapping rule, and with ROBOT1_ARGS. `node` is the node's fully
# qualified name, under which its parameter services are.
PLAIN = {
    "map": "map",
    "pose": "pose",
    "tf": "tf",
    "tf_static": "tf_static",
    "command": "explore/command",
    "resume": "explore/resume",
    "goal": "explore/goal",
    "markers": "explore/frontiers",
    "status": "explore/status",
    "action": "navigate_to_pose",
    "node": "frontier_explore",
}
# `--namespaced`: a launch file's Node(namespace="robot1", parameters=[{"map_topic": "map"}],
# remappings=[...]) for a robot that shares a map: a relative name remapped to an absolute
# one (map), absolute defaults remapped to relative names (the pose, TF and the action, as a
# namespaced Nav2 and AMCL name them), and the node's own relative names left to the
# namespace. As in a launch file, the rules are there for either source of the pose: the
# TF ones remap nothing when it comes from a topic, the pose's nothing with TF.
ROBOT1_ARGS = [
    "--ros-args",
    "-p", "map_topic:=map",
    "-r", "__ns:=/robot1",
    "-r", "map:=/shared_map",
    "-r", "/pose:=amcl_pose",
    "-r", "/tf:=tf",
    "-r", "/tf_static:=tf_static",
    "-r", "/navigate_to_pose:=navigate_to_pose",
]
ROBOT1 = {
    "map": "shared_map",
    "pose": "robot1/amcl_pose",
    "tf": "robot1/tf",
    "tf_static": "robot1/tf_static",
    "command": "robot1/explore/command",
    "resume": "robot1/explore/resume",
    "goal": "robot1/explore/goal",
    "markers": "robot1/explore/frontiers",
    "status": "robot1/explore/status",
    "action": "robot1/navigate_to_pose",
    "node": "robot1/frontier_explore",
}
# The names `fastdds_peer` takes as arguments.
PEER_NAMES = ["map", "pose", "tf", "tf_static", "command", "goal", "status", "action"]
# The topics every ROS 2 node's participant may use besides its own, whatever its namespace.
ROS_GLOBAL = {"ros_discovery_info", "rt/parameter_events", "rt/rosout", "rt/clock"}


def expected_endpoints(names, pose):
    """The DDS topics of the node's readers and writers: its topics, and the action's three
    services and two topics (created in publish-only mode too)."""
    topics = [names[k] for k in ("map", "command", "resume", "goal", "markers", "status")]
    topics += [names["tf"], names["tf_static"]] if pose == "tf" else [names["pose"]]
    action = names["action"] + "/_action/"
    out = {"rt/" + t for t in topics} | {f"rt/{action}feedback", f"rt/{action}status"}
    for service in ("send_goal", "get_result", "cancel_goal"):
        out |= {f"rq/{action}{service}Request", f"rr/{action}{service}Reply"}
    return out


class Endpoints:
    """The DDS topics of the node's readers and writers, as discovery announces them to a
    Cyclone participant of its own (so for either peer). The node's participant is the one
    that writes `ros_discovery_info`, as every ROS 2 node's does; the peers' do not."""

    def __init__(self, domain):
        self.dp = DomainParticipant(domain)
        self.writers = BuiltinDataReader(self.dp, BuiltinTopicDcpsPublication)
        self.readers = BuiltinDataReader(self.dp, BuiltinTopicDcpsSubscription)
        self.seen = set()  # (participant, is a writer, topic)

    def poll(self):
        for writer, r in ((True, self.writers), (False, self.readers)):
            for e in r.take(N=256):
                if isinstance(e, DcpsEndpoint):
                    self.seen.add((e.participant_key, writer, e.topic_name))

    def node_topics(self):
        self.poll()
        nodes = {p for p, writer, t in self.seen if writer and t == "ros_discovery_info"}
        return {t for p, _, t in self.seen if p in nodes}


class CyclonePeer:
    """The mock's DDS side in Cyclone DDS, as rmw_cyclonedds_cpp would carry it."""

    rmw = "rmw_cyclonedds_cpp"

    def __init__(self, domain, pose, humble, names):
        dp = DomainParticipant(domain)
        self.pose_kind = pose
        self.humble = humble
        xcdr1 = Policy.DataRepresentation(use_cdrv0_representation=True)
        reliable = Qos(Policy.Reliability.Reliable(duration(seconds=1)), Policy.History.KeepLast(10), xcdr1)
        latched = Qos(
            Policy.Reliability.Reliable(duration(seconds=1)),
            Policy.Durability.TransientLocal,
            Policy.History.KeepLast(1),
            xcdr1,
        )
        self.map_w = DataWriter(dp, Topic(dp, "rt/" + names["map"], OccupancyGrid), qos=latched)
        if pose == "tf":
            self.tf_w = DataWriter(dp, Topic(dp, "rt/" + names["tf"], TFMessage), qos=reliable)
            # Kept: a writer that goes takes its latched sample with it.
            self.static_w = DataWriter(dp, Topic(dp, "rt/" + names["tf_static"], TFMessage), qos=latched)
            self.static_w.write(TFMessage([transform(*e) for e in STATIC_EDGES]))
        else:
            pose_type = PoseStamped if pose == "stamped" else PoseWithCovarianceStamped
            self.pose_w = DataWriter(dp, Topic(dp, "rt/" + names["pose"], pose_type), qos=reliable)
        self.cmd_w = DataWriter(dp, Topic(dp, "rt/" + names["command"], String), qos=reliable)
        self.goal_r = DataReader(dp, Topic(dp, "rt/" + names["goal"], PoseStamped), qos=reliable)
        self.status_r = DataReader(dp, Topic(dp, "rt/" + names["status"], String), qos=latched)
        base = names["action"] + "/_action/"

        def service(name, req, rep):
            return (
                DataReader(dp, Topic(dp, f"rq/{base}{name}Request", req), qos=reliable),
                DataWriter(dp, Topic(dp, f"rr/{base}{name}Reply", rep), qos=reliable),
            )

        self.send_goal = service("send_goal", SendGoalRequest, SendGoalReply)
        self.get_result = service(
            "get_result", GetResultRequest, HumbleGetResultReply if humble else GetResultReply
        )
        self.cancel = service("cancel_goal", CancelRequest, CancelReply)
        self.pending = {}  # token → the request id to repeat
        self.token = 0

    def map(self, w, h, res, data):
        identity = Quaternion(0.0, 0.0, 0.0, 1.0)
        info = MapMetaData(stamp(), res, w, h, Pose(Point(0.0, 0.0, 0.0), identity))
        self.map_w.write(OccupancyGrid(Header(stamp(), "map"), info, data))

    def pose(self, x, y):
        pose = Pose(Point(x, y, 0.0), Quaternion(0.0, 0.0, 0.0, 1.0))
        if self.pose_kind == "tf":
            self.tf_w.write(TFMessage([transform(*e) for e in tf_edges(x, y)]))
        elif self.pose_kind == "stamped":
            self.pose_w.write(PoseStamped(Header(stamp(), "map"), pose))
        else:
            covariance = [0.0] * 36
            covariance[0] = covariance[7] = 0.01
            covariance[35] = 0.005
            self.pose_w.write(PoseWithCovarianceStamped(Header(stamp(), "map"), PoseWithCovariance(pose, covariance)))

    def command(self, text):
        self.cmd_w.write(String(text))

    def _keep(self, request_id):
        self.token += 1
        self.pending[self.token] = request_id
        return self.token

    def events(self):
        out = []
        for g in self.goal_r.take(N=16):
            if isinstance(g, PoseStamped):
                out.append(("goal", g.pose.position.x, g.pose.position.y, g.header.frame_id))
        for s in self.status_r.take(N=16):
            if isinstance(s, String):
                out.append(("status", s.data))
        for r in self.send_goal[0].take(N=16):
            if isinstance(r, SendGoalRequest):
                p = r.goal.pose.pose.position
                out.append(("send_goal", self._keep(r.request_id), bytes(r.goal_id.uuid).hex(), p.x, p.y))
        for r in self.get_result[0].take(N=16):
            if isinstance(r, GetResultRequest):
                out.append(("get_result", self._keep(r.request_id), bytes(r.goal_id.uuid).hex()))
        for r in self.cancel[0].take(N=16):
            if isinstance(r, CancelRequest):
                out.append(("cancel", self._keep(r.request_id)))
        return out

    def goal_reply(self, token, accepted):
        self.send_goal[1].write(SendGoalReply(self.pending.pop(token), accepted, stamp()))

    def result_reply(self, token, status):
        if self.humble:
            reply = HumbleGetResultReply(self.pending.pop(token), status, HumbleResult(0))
        else:
            reply = GetResultReply(self.pending.pop(token), status, NavResult(0, ""))
        self.get_result[1].write(reply)

    def cancel_reply(self, token):
        self.cancel[1].write(CancelReply(self.pending.pop(token), 0, []))

    def close(self):
        pass


class FastDdsPeer:
    """The mock's DDS side in Fast DDS: `fastdds_peer`, driven line by line."""

    rmw = "rmw_fastrtps_cpp"

    def __init__(self, domain, pose, binary, names):
        self.proc = subprocess.Popen(
            [binary, str(domain), pose] + [f"{k}={names[k]}" for k in PEER_NAMES],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        os.set_blocking(self.proc.stdout.fileno(), False)
        self.buf = ""
        self.tf = pose == "tf"
        if self.tf:
            self._send(self._edges("tf_static", STATIC_EDGES))

    def _send(self, line):
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()

    @staticmethod
    def _edges(topic, edges):
        return topic + "".join(" " + " ".join(map(str, e)) for e in edges)

    def map(self, w, h, res, data):
        self._send(f"map {w} {h} {res} " + " ".join(map(str, data)))

    def pose(self, x, y):
        self._send(self._edges("tf", tf_edges(x, y)) if self.tf else f"pose {x} {y}")

    def command(self, text):
        self._send(f"command {text}")

    def events(self):
        try:
            self.buf += os.read(self.proc.stdout.fileno(), 1 << 20).decode()
        except BlockingIOError:
            pass
        *lines, self.buf = self.buf.split("\n")
        out = []
        for line in lines:
            kind, _, rest = line.partition(" ")
            f = rest.split(" ")
            if kind == "goal":
                out.append(("goal", float(f[0]), float(f[1]), f[2] if len(f) > 2 else ""))
            elif kind == "status":
                out.append(("status", rest))
            elif kind == "send_goal":
                out.append(("send_goal", int(f[0]), f[1], float(f[2]), float(f[3])))
            elif kind == "get_result":
                out.append(("get_result", int(f[0]), f[1]))
            elif kind == "cancel":
                out.append(("cancel", int(f[0])))
        return out

    def goal_reply(self, token, accepted):
        self._send(f"goal_reply {token} {int(accepted)}")

    def result_reply(self, token, status):
        self._send(f"result_reply {token} {status}")

    def cancel_reply(self, token):
        self._send(f"cancel_reply {token}")

    def close(self):
        self.proc.stdin.close()
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--node", required=True, help="the frontier-ros binary")
    ap.add_argument("--dds", choices=["cyclone", "fastdds"], default="cyclone")
    ap.add_argument("--fastdds-peer", help="the fastdds_peer binary (with --dds fastdds)")
    ap.add_argument("--mode", choices=["action", "publish-only"], default="action")
    ap.add_argument("--pose", choices=["covariance", "stamped", "tf"],
                    help="how the robot's pose goes to the node: PoseWithCovarianceStamped (the "
                         "default with --mode action), PoseStamped (with publish-only) or TF")
    ap.add_argument("--nav2", choices=["jazzy", "humble"], default="jazzy",
                    help="the NavigateToPose result's layout (humble: empty; --dds cyclone)")
    ap.add_argument("--namespaced", action="store_true",
                    help="run the node in /robot1 with remapping rules (ROBOT1_ARGS); the peer "
                         "uses the names they give")
    ap.add_argument("--domain", type=int, default=150 + os.getpid() % 50)
    ap.add_argument("--limit", type=float, default=90.0, help="seconds before giving up")
    ap.add_argument("-p", dest="extra", action="append", default=[], metavar="NAME:=VALUE",
                    help="one more parameter for the node")
    args = ap.parse_args()
    if args.dds == "fastdds" and not args.fastdds_peer:
        ap.error("--dds fastdds needs --fastdds-peer")
    if args.dds == "fastdds" and args.nav2 == "humble":
        ap.error("--nav2 humble is served by --dds cyclone only")
    pose = args.pose or ("stamped" if args.mode == "publish-only" else "covariance")
    params = [
        ("strategy", "cf-rr"),
        ("sensor", "los:r=3"),
        ("clearance", "0"),
        ("min_frontier_size", "0"),
        ("planner_frequency", "5"),
        # The default PoseWithCovarianceStamped (slam_toolbox's, AMCL's) with Nav2, the
        # other type in publish-only mode, unless --pose says.
        ("pose_type", {"covariance": "PoseWithCovarianceStamped", "stamped": "PoseStamped", "tf": "tf"}[pose]),
        ("goal_tolerance", "0.3"),
        ("publish_only", "true" if args.mode == "publish-only" else "false"),
        # With Nav2, back to the start when done.
        ("return_to_init", "true" if args.mode == "action" else "false"),
    ]
    cmd = [args.node, "--domain", str(args.domain)]
    for k, v in params:
        cmd += ["-p", f"{k}:={v}"]
    for p in args.extra:
        cmd += ["-p", p]
    names = ROBOT1 if args.namespaced else PLAIN
    if args.namespaced:
        cmd += ROBOT1_ARGS
    endpoints = Endpoints(args.domain)
    if args.dds == "cyclone":
        peer = CyclonePeer(args.domain, pose, args.nav2 == "humble", names)
    else:
        peer = FastDdsPeer(args.domain, pose, args.fastdds_peer, names)
    node = subprocess.Popen(cmd, env=dict(os.environ, RMW_IMPLEMENTATION=peer.rmw))
    try:
        ok = run(args, peer, endpoints, names, pose)
    finally:
        node.terminate()
        try:
            node.wait(timeout=10)
        except subprocess.TimeoutExpired:
            node.kill()
        peer.close()
    sys.exit(0 if ok else 1)


def run(args, peer, endpoints, names, pose):
    action = args.mode == "action"
    world = World()
    robot = START

    def publish():
        world.sense(*robot)
        peer.map(world.w, world.h, RES, world.grid())
        peer.pose((robot[0] + 0.5) * RES, (robot[1] + 0.5) * RES)

    status, goals, nav_goals = [], [], []
    ends = {}  # goal id → the status its result reports
    paused_at, paused_goals, resumed = None, None, False
    deadline = time.time() + args.limit
    last = 0.0
    while time.time() < deadline:
        if time.time() - last > 0.5:
            publish()
            endpoints.poll()
            last = time.time()
        for e in peer.events():
            if e[0] == "status":
                status.append(e[1])
                print("status:", e[1], flush=True)
                if e[1] == "paused":
                    paused_at = time.time()
            elif e[0] == "goal":
                _, x, y, frame = e
                goals.append((x, y))
                print(f"goal {len(goals)}: ({x:.2f}, {y:.2f}) in frame {frame!r}", flush=True)
                if not action:
                    # Drive there: the cell that holds the goal.
                    robot = (int(x // RES), int(y // RES))
                    publish()
                    last = time.time()
                if len(goals) == 2:
                    peer.command("stop")
            elif e[0] == "send_goal":
                _, token, uuid, x, y = e
                nav_goals.append((x, y))
                print(f"nav2: goal {len(nav_goals)} ({x:.2f}, {y:.2f})", flush=True)
                peer.goal_reply(token, True)
                if len(nav_goals) == 1:
                    ends[uuid] = ABORTED
                else:
                    ends[uuid] = SUCCEEDED
                    robot = (int(x // RES), int(y // RES))
                    publish()
                    last = time.time()
            elif e[0] == "get_result":
                _, token, uuid = e
                peer.result_reply(token, ends.get(uuid, ABORTED))
            elif e[0] == "cancel":
                peer.cancel_reply(e[1])
        if status and status[-1].startswith("done"):
            break
        # A goal sent before the node paused may still come (the two topics are not
        # ordered with each other); from half a second after, none may.
        if paused_at is not None and paused_goals is None and time.time() - paused_at > 0.5:
            paused_goals = len(goals)
        if paused_goals is not None and not resumed and time.time() - paused_at > 2.5:
            if len(goals) != paused_goals:
                print("FAIL: a goal while paused", flush=True)
                return False
            peer.command("resume")
            resumed = True
        time.sleep(0.02)

    checks = [
        ("the node saw the map and the pose and sent goals", len(goals) > 1),
        ("it paused on 'stop' and went on after 'resume'", "paused" in status and resumed
         and "exploring" in status[status.index("paused") + 1:]),
        ("it ended with 'done: explored'", bool(status) and status[-1].startswith("done: explored")),
        ("every free cell is known", world.unknown_free() == 0),
    ]
    if action:
        start = ((START[0] + 0.5) * RES, (START[1] + 0.5) * RES)
        checks += [
            ("Nav2 received the goals", len(nav_goals) > 1),
            ("it drove back to the start and said so", bool(nav_goals) and nav_goals[-1] == start
             and bool(status) and status[-1].endswith("; returned to the start pose")),
            ("the aborted goal never came again", bool(nav_goals) and nav_goals[0] not in nav_goals[1:]),
        ]
    else:
        checks.append(("Nav2 received nothing", not nav_goals))
    # The node's DDS endpoints: on `names`, and besides only on ROS 2's global topics and
    # under its fully qualified name (ros2-client's parameter services).
    found, expected = endpoints.node_topics(), expected_endpoints(names, pose)
    missing = expected - found
    others = {
        t for t in found - expected
        if t not in ROS_GLOBAL and not t.startswith((f"rq/{names['node']}/", f"rr/{names['node']}/"))
    }
    for t in sorted(missing):
        print("no endpoint of the node on", t, flush=True)
    for t in sorted(others):
        print("an endpoint of the node on", t, flush=True)
    checks.append((f"its DDS endpoints are rcl's names (rt/{names['map']}, rt/{names['status']}, "
                   f"rq/{names['action']}/_action/send_goalRequest, …), and no others",
                   not missing and not others))
    for what, ok in checks:
        print(("ok    " if ok else "FAIL  ") + what, flush=True)
    return all(ok for _, ok in checks)


if __name__ == "__main__":
    main()
