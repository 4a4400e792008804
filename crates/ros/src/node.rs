//! The ROS 2 node: topics and Nav2's action around an [`Explorer`].
//!
//! | direction | name (default) | type | what |
//! |---|---|---|---|
//! | in | `/map` | `nav_msgs/msg/OccupancyGrid` | the SLAM map, transient-local and reliable like map_server and slam_toolbox |
//! | in | `/pose` | `geometry_msgs/msg/PoseWithCovarianceStamped` (or `PoseStamped`) | the robot's pose in the map frame |
//! | in | `/explore/resume` | `std_msgs/msg/Bool` | explore_lite's: `true` starts or resumes, `false` stops |
//! | in | `/explore/command` | `std_msgs/msg/String` | `start`, `stop`, `resume`, `return_to_init` |
//! | out | `/navigate_to_pose` | `nav2_msgs/action/NavigateToPose` | goals (not in publish-only mode) |
//! | out | `/explore/goal` | `geometry_msgs/msg/PoseStamped` | every goal chosen |
//! | out | `/explore/frontiers` | `visualization_msgs/msg/MarkerArray` | frontier cells and goal candidates |
//! | out | `/explore/status` | `std_msgs/msg/String` | `idle`, `exploring`, `waiting: <why>`, `paused[: <why>]`, `returning`, `done: <reason>`, `shut down` |
//!
//! The names are those with no namespace and no remapping rule: every one is resolved as
//! rcl resolves it ([`crate::names`]; [`run_with`]). The `explore/…` ones are relative, in
//! the node's namespace (`/robot1/explore/status` under `__ns:=/robot1`), as explore_lite's
//! are; the others absolute, as SLAM nodes and Nav2 name them.
//!
//! The robot's pose comes from a pose topic (AMCL's `/amcl_pose`, slam_toolbox's `/pose`),
//! or with `pose_type: tf` from `/tf` and `/tf_static` (`robot_base_frame` chained up to the
//! map frame), for localisation that publishes no pose topic. Decisions run on map updates,
//! on poses (the re-plan policy's checks are O(1)), when Nav2 ends a goal, and at
//! `planner_frequency`.

use std::cell::RefCell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use futures::{FutureExt, StreamExt};
use ros2_client::action::ActionClientQosPolicies;
use ros2_client::action_msgs::GoalStatusEnum;
use ros2_client::builtin_interfaces::Time as RosTime;
use ros2_client::qos::{Durability, History};
use ros2_client::unique_identifier_msgs::UUID;
use ros2_client::{
    ActionTypeName, Context, ContextOptions, MessageTypeName, Name, Node, NodeName, NodeOptions,
    QosProfile, ServiceMapping,
};
use serde::{Deserialize, Serialize, de::DeserializeOwned};

use record::mcap_write::markers;
use record::msgs::{
    Header, NavigateToPoseGoal, OccupancyGrid, Pose, PoseStamped, PoseWithCovarianceStamped,
    TfMessage, Time,
};

use crate::explorer::{Check, Decision, Explorer, StopReason};
use crate::names::{
    COMMAND_TOPIC, NameResolver, OwnTopics, RESUME_TOPIC, STATUS_TOPIC, TF_STATIC_TOPIC, TF_TOPIC,
};
use crate::params::{Params, PoseType};
use crate::tf::{TfTree, frame_name, planar_pose};

/// A message of the `record` crate as ros2-client sends it (CDR of the struct itself).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Ros<T>(pub T);

impl<T: Serialize + DeserializeOwned> ros2_client::Message for Ros<T> {}

/// `std_msgs/msg/Bool`.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub struct Bool {
    /// The value.
    pub data: bool,
}

/// `std_msgs/msg/String`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Text {
    /// The text.
    pub data: String,
}

/// Send the poses of a pose topic (`pose` picks a message's pose) to the event loop.
async fn forward_poses<M: Serialize + DeserializeOwned + 'static>(
    sub: ros2_client::Subscription<Ros<M>>,
    topic: String,
    tx: async_channel::Sender<Event>,
    pose: fn(M) -> (String, Pose),
) {
    let mut s = std::pin::pin!(sub.async_stream());
    // The last problem logged, so that a pose stream repeats none.
    let mut said = String::new();
    while let Some(m) = s.next().await {
        match m {
            Ok((Ros(msg), _)) => {
                let (frame, p) = pose(msg);
                match planar_pose(&p) {
                    Ok((x, y, yaw)) => {
                        let _ = tx.send(Event::Pose(x, y, yaw, frame)).await;
                    }
                    Err(e) if e != said => {
                        log::warn!("pose on {topic} skipped: {e}");
                        said = e;
                    }
                    Err(_) => {}
                }
            }
            Err(e) => log::warn!("pose message on {topic} skipped: {e:?}"),
        }
    }
}

/// Send the pose of frame `base` in the map's frame (`map_frame`, the latest map
/// message's), from the latest transforms of `/tf` and `/tf_static`, to the event loop at
/// every TF message that completes the chain.
async fn forward_tf(
    tf_sub: ros2_client::Subscription<Ros<TfMessage>>,
    static_sub: ros2_client::Subscription<Ros<TfMessage>>,
    tx: async_channel::Sender<Event>,
    base: String,
    map_frame: Rc<RefCell<String>>,
) {
    let mut tree = TfTree::new();
    // The last problem logged, so that a TF stream at 50 Hz repeats none.
    let mut said = String::new();
    let dynamic = std::pin::pin!(tf_sub.async_stream());
    let fixed = std::pin::pin!(static_sub.async_stream());
    let mut both = futures::stream::select(dynamic, fixed);
    while let Some(m) = both.next().await {
        let msg = match m {
            Ok((Ros(msg), _)) => msg,
            Err(e) => {
                log::warn!("TF message skipped: {e:?}");
                continue;
            }
        };
        for t in &msg.transforms {
            if let Err(e) = tree.set(t)
                && e != said
            {
                log::warn!("TF: {e}; skipped");
                said = e;
            }
        }
        let target = map_frame.borrow().clone();
        match tree.lookup(&target, &base) {
            Ok((x, y, yaw)) => {
                let _ = tx.send(Event::Pose(x, y, yaw, target)).await;
            }
            Err(e) if e != said => {
                log::info!("TF: {e}");
                said = e;
            }
            Err(_) => {}
        }
    }
}

/// The navigation action client of the node. Only the goal's end status is read, so its
/// result and feedback are read as `()` (nothing): Humble's empty result, Jazzy's error code
/// and later additions all decode.
type NavClient = ros2_client::action::ActionClient<Ros<NavigateToPoseGoal>, (), ()>;

/// What the node is doing.
#[derive(Clone, Debug, PartialEq)]
pub enum Mode {
    /// Waiting for `start`.
    Idle,
    /// Deciding and sending goals.
    Exploring,
    /// Stopped by `stop` (`None`), or by what it says; `resume` goes on.
    Paused(Option<String>),
    /// Driving back to the start pose.
    Returning,
    /// Finished, with the reason.
    Done(String),
}

impl Mode {
    fn status(&self) -> String {
        match self {
            Mode::Idle => "idle".into(),
            Mode::Exploring => "exploring".into(),
            Mode::Paused(None) => "paused".into(),
            Mode::Paused(Some(why)) => format!("paused: {why}"),
            Mode::Returning => "returning".into(),
            Mode::Done(r) => format!("done: {r}"),
        }
    }
}

/// Everything the event loop reacts to.
enum Event {
    Map(OccupancyGrid),
    /// x, y, yaw and the frame the pose is given in ("": not said).
    Pose(f64, f64, f64, String),
    Command(String),
    Tick,
    /// Nav2 accepted goal `seq` as `id`.
    Accepted(u64, UUID),
    /// Goal `seq` ended.
    Ended(u64, Outcome),
    /// Nav2's NavigateToPose server has been discovered.
    NavReady,
    /// The backoff after goal `seq` was refused is over: send the goal again.
    Retry(u64),
    Shutdown,
}

/// How a goal ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outcome {
    Succeeded,
    /// Aborted by Nav2 (or its result lost).
    Failed,
    Canceled,
    /// Nav2 rejected the goal (bt_navigator does until it is active).
    Rejected,
    /// No answer to the goal request within [`GOAL_ANSWER_WAIT`].
    NoAnswer,
}

/// How often the node warns while no map or no pose has come.
const STARVED_WARN_EVERY: Duration = Duration::from_secs(10);

/// How long a goal request waits for Nav2's answer before it is sent again later.
const GOAL_ANSWER_WAIT: Duration = Duration::from_secs(10);

/// The wait before a goal Nav2 refused or left unanswered is sent again: 1 s, doubling at
/// each refusal in a row, at most 30 s.
fn retry_backoff(refusals: u32) -> Duration {
    Duration::from_secs(1u64 << refusals.saturating_sub(1).min(5)).min(Duration::from_secs(30))
}

/// How long shutting down waits for Nav2 to answer the cancel of the goal in flight.
pub const SHUTDOWN_CANCEL_WAIT: Duration = Duration::from_secs(1);

/// The QoS of `/map`: reliable, transient local, keep last 1 (map_server, slam_toolbox).
pub fn map_qos() -> QosProfile {
    QosProfile::publisher_default()
        .durability(Durability::TransientLocal)
        .history(History::KeepLast { depth: 1 })
}

/// The QoS of the action's services and feedback (volatile) and status (transient local).
pub fn action_qos() -> ActionClientQosPolicies {
    let service = QosProfile::publisher_default()
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth: 1 });
    ActionClientQosPolicies {
        goal_service: service.clone(),
        result_service: service.clone(),
        cancel_service: service.clone(),
        feedback_subscription: service.clone(),
        status_subscription: service.durability(Durability::TransientLocal),
    }
}

/// A DDS context on `domain_id` (ROS_DOMAIN_ID).
pub fn context(domain_id: u16) -> anyhow::Result<Context> {
    Context::with_options(ContextOptions::new().domain_id(domain_id))
        .map_err(|e| anyhow::anyhow!("cannot start DDS on domain {domain_id}: {e:?}"))
}

/// A name in the root namespace (`/map`), or relative to it.
pub fn topic_name(s: &str) -> anyhow::Result<Name> {
    ros_name(s).map_err(|e| anyhow::anyhow!("topic name '{s}': {e}"))
}

/// `s` as a ROS 2 name, or what is wrong with it.
fn ros_name(s: &str) -> Result<Name, String> {
    let s = s.trim_start_matches('/');
    let (ns, base) = match s.rsplit_once('/') {
        Some((ns, base)) => (format!("/{ns}"), base),
        None => ("/".to_string(), s),
    };
    Name::new(&ns, base).map_err(|e| format!("{e:?}"))
}

/// The name given by parameter `param` (`map_topic`, ...), checked by ROS 2's rules; an
/// error names the parameter and its value.
pub fn param_topic_name(param: &str, value: &str) -> anyhow::Result<Name> {
    ros_name(value).map_err(|e| {
        anyhow::anyhow!(
            "{param}: expected a ROS 2 name (letters, digits and '_' between '/'), found \
             '{value}' ({e})"
        )
    })
}

/// Create a topic of `package/Type` on `node`.
pub fn topic(
    node: &Node,
    name: &str,
    package: &str,
    ty: &str,
) -> anyhow::Result<ros2_client::dds::rustdds::Topic> {
    node.create_topic(
        &topic_name(name)?,
        MessageTypeName::new(package, ty),
        &QosProfile::publisher_default(),
    )
    .map_err(|e| anyhow::anyhow!("topic {name}: {e:?}"))
}

fn stamp(now: Instant, t0: Instant) -> Time {
    Time::from_secs((now - t0).as_secs_f64())
}

/// Run the node until `stop` fires (or the channel closes); returns the final mode. The node
/// is `node_name` in the root namespace, with no remapping rules.
pub fn run(
    params: Params,
    node_name: &str,
    ctx: &Context,
    stop: async_channel::Receiver<()>,
) -> anyhow::Result<Mode> {
    let names = NameResolver::new(node_name, &[]).map_err(|e| anyhow::anyhow!("node name: {e}"))?;
    run_with(params, &names, ctx, stop)
}

/// [`run`] with the node's name, namespace and remapping rules (`--ros-args -r`): every
/// topic and action name is resolved through `names`, as rcl resolves them.
pub fn run_with(
    mut params: Params,
    names: &NameResolver,
    ctx: &Context,
    stop: async_channel::Receiver<()>,
) -> anyhow::Result<Mode> {
    let cfg = params.explorer_config().map_err(|e| anyhow::anyhow!(e))?;
    let period = params.planner_period().map_err(|e| anyhow::anyhow!(e))?;
    // The names as the node uses them, before remapping (for the rules that match none).
    let mut used = vec![
        params.map_topic.clone(),
        params.navigate_action.clone(),
        params.goal_topic.clone(),
        params.markers_topic.clone(),
        RESUME_TOPIC.to_string(),
        COMMAND_TOPIC.to_string(),
        STATUS_TOPIC.to_string(),
    ];
    match params.pose_type {
        PoseType::Tf => used.extend([TF_TOPIC.to_string(), TF_STATIC_TOPIC.to_string()]),
        _ => used.push(params.pose_topic.clone()),
    }
    params.resolve_names(names).map_err(anyhow::Error::msg)?;
    let own = names.own_topics().map_err(anyhow::Error::msg)?;
    for (param, value) in [
        ("map_topic", &params.map_topic),
        ("pose_topic", &params.pose_topic),
        ("navigate_action", &params.navigate_action),
        ("goal_topic", &params.goal_topic),
        ("markers_topic", &params.markers_topic),
    ] {
        param_topic_name(param, value)?;
    }
    let node_name = names.node();
    let used: Vec<&str> = used.iter().map(String::as_str).collect();
    for rule in names.unused_rules(&used) {
        // Info, not a warning: launch files often give every node the same rules (/tf).
        let expanded: Vec<String> = used
            .iter()
            .map(|n| names.expand(n).unwrap_or_else(|_| n.to_string()))
            .collect();
        log::info!(
            "remapping rule '{rule}' matches none of the node's names ({}): it remaps nothing",
            expanded.join(", ")
        );
    }
    log::info!(
        "node {}: map {}, pose {}, navigate {}, goals {}, markers {}, status {}, commands {} \
         and {}",
        names.fully_qualified_node_name(),
        params.map_topic,
        if params.pose_type == PoseType::Tf {
            format!("from {} and {}", own.tf, own.tf_static)
        } else {
            params.pose_topic.clone()
        },
        params.navigate_action,
        params.goal_topic,
        params.markers_topic,
        own.status,
        own.command,
        own.resume
    );
    let mut node = ctx
        .new_node(
            // In its namespace (`ros2 node list` shows /NS/NAME), whose relative names
            // resolve there too; every name here is resolved already (absolute).
            NodeName::new(names.namespace(), node_name)
                .map_err(|e| anyhow::anyhow!("node name: {e:?}"))?,
            NodeOptions::new().enable_rosout(false),
        )
        .map_err(|e| anyhow::anyhow!("cannot create node {node_name}: {e:?}"))?;
    let map_t = topic(&node, &params.map_topic, "nav_msgs", "OccupancyGrid")?;
    let map_sub = node
        .create_subscription::<Ros<OccupancyGrid>>(&map_t, Some(map_qos()))
        .map_err(|e| anyhow::anyhow!("{e:?}"))?;
    let resume_t = topic(&node, &own.resume, "std_msgs", "Bool")?;
    let command_t = topic(&node, &own.command, "std_msgs", "String")?;
    let goal_t = topic(&node, &params.goal_topic, "geometry_msgs", "PoseStamped")?;
    let markers_t = topic(
        &node,
        &params.markers_topic,
        "visualization_msgs",
        "MarkerArray",
    )?;
    let status_t = topic(&node, &own.status, "std_msgs", "String")?;
    let reliable = QosProfile::publisher_default().history(History::KeepLast { depth: 10 });
    let latched = reliable
        .clone()
        .durability(Durability::TransientLocal)
        .history(History::KeepLast { depth: 1 });
    let err = |e| anyhow::anyhow!("{e:?}");
    let resume_sub = node
        .create_subscription::<Bool>(&resume_t, Some(reliable.clone()))
        .map_err(err)?;
    let command_sub = node
        .create_subscription::<Text>(&command_t, Some(reliable.clone()))
        .map_err(err)?;
    let goal_pub = node
        .create_publisher::<Ros<PoseStamped>>(&goal_t, Some(reliable.clone()))
        .map_err(err)?;
    let markers_pub = node
        .create_publisher::<Ros<record::msgs::MarkerArray>>(&markers_t, Some(reliable.clone()))
        .map_err(err)?;
    let status_pub = node
        .create_publisher::<Text>(&status_t, Some(latched))
        .map_err(err)?;
    let rmw = std::env::var("RMW_IMPLEMENTATION").ok();
    let mapping = match params.service_mapping.resolve(rmw.as_deref()) {
        crate::params::ServiceMapping::Cyclone => ServiceMapping::Cyclone,
        _ => ServiceMapping::Enhanced,
    };
    if !params.publish_only {
        log::info!(
            "NavigateToPose over the {mapping:?} service mapping (service_mapping: {:?}, \
             RMW_IMPLEMENTATION: {})",
            params.service_mapping,
            rmw.as_deref().unwrap_or("unset")
        );
    }
    let nav: Rc<NavClient> = Rc::new(
        node.create_action_client(
            mapping,
            &topic_name(&params.navigate_action)?,
            &ActionTypeName::new("nav2_msgs", "NavigateToPose"),
            action_qos(),
        )
        .map_err(err)?,
    );

    let ex = smol::LocalExecutor::new();
    ex.spawn(node.spinner().map_err(err)?.spin()).detach();
    let (tx, rx) = async_channel::unbounded::<Event>();
    {
        let tx = tx.clone();
        ex.spawn(async move {
            let mut s = std::pin::pin!(map_sub.async_stream());
            while let Some(m) = s.next().await {
                match m {
                    Ok((Ros(msg), _)) => {
                        let _ = tx.send(Event::Map(msg)).await;
                    }
                    Err(e) => log::warn!("map message skipped: {e:?}"),
                }
            }
        })
        .detach();
    }
    // The map's frame, from its messages ("map" until the first): goals, markers and the
    // TF lookup are in it, and poses must be.
    let map_frame = Rc::new(RefCell::new("map".to_string()));
    match params.pose_type {
        PoseType::WithCovariance => {
            let t = topic(
                &node,
                &params.pose_topic,
                "geometry_msgs",
                "PoseWithCovarianceStamped",
            )?;
            let sub = node
                .create_subscription::<Ros<PoseWithCovarianceStamped>>(&t, Some(reliable.clone()))
                .map_err(err)?;
            ex.spawn(forward_poses(
                sub,
                params.pose_topic.clone(),
                tx.clone(),
                |m| (m.header.frame_id, m.pose.pose),
            ))
            .detach();
        }
        PoseType::Stamped => {
            let t = topic(&node, &params.pose_topic, "geometry_msgs", "PoseStamped")?;
            let sub = node
                .create_subscription::<Ros<PoseStamped>>(&t, Some(reliable.clone()))
                .map_err(err)?;
            ex.spawn(forward_poses(
                sub,
                params.pose_topic.clone(),
                tx.clone(),
                |m| (m.header.frame_id, m.pose),
            ))
            .detach();
        }
        PoseType::Tf => {
            // TF: /tf (odometry, SLAM) and /tf_static (the robot's description, latched),
            // chained from the robot's base frame to the map frame at every message.
            let dynamic = topic(&node, &own.tf, "tf2_msgs", "TFMessage")?;
            let fixed = topic(&node, &own.tf_static, "tf2_msgs", "TFMessage")?;
            let tf_qos = QosProfile::publisher_default().history(History::KeepLast { depth: 100 });
            let tf_sub = node
                .create_subscription::<Ros<TfMessage>>(&dynamic, Some(tf_qos.clone()))
                .map_err(err)?;
            let static_sub = node
                .create_subscription::<Ros<TfMessage>>(
                    &fixed,
                    Some(tf_qos.durability(Durability::TransientLocal)),
                )
                .map_err(err)?;
            let base = params.robot_base_frame.clone();
            ex.spawn(forward_tf(
                tf_sub,
                static_sub,
                tx.clone(),
                base,
                map_frame.clone(),
            ))
            .detach();
        }
    }
    {
        let tx = tx.clone();
        let topic = own.resume.clone();
        ex.spawn(async move {
            let mut s = std::pin::pin!(resume_sub.async_stream());
            while let Some(m) = s.next().await {
                match m {
                    Ok((b, _)) => {
                        let c = if b.data { "resume" } else { "stop" };
                        let _ = tx.send(Event::Command(c.into())).await;
                    }
                    Err(e) => log::warn!(
                        "message on {topic} skipped: expected a std_msgs/msg/Bool, found one \
                         that does not decode ({e:?})"
                    ),
                }
            }
        })
        .detach();
    }
    {
        let tx = tx.clone();
        let topic = own.command.clone();
        ex.spawn(async move {
            let mut s = std::pin::pin!(command_sub.async_stream());
            while let Some(m) = s.next().await {
                match m {
                    Ok((t, _)) => {
                        let _ = tx.send(Event::Command(t.data)).await;
                    }
                    Err(e) => log::warn!(
                        "message on {topic} skipped: expected a std_msgs/msg/String, found one \
                         that does not decode ({e:?})"
                    ),
                }
            }
        })
        .detach();
    }
    {
        let tx = tx.clone();
        ex.spawn(async move {
            let mut t = smol::Timer::interval(period);
            while t.next().await.is_some() {
                if tx.send(Event::Tick).await.is_err() {
                    break;
                }
            }
        })
        .detach();
    }
    {
        let tx = tx.clone();
        ex.spawn(async move {
            let _ = stop.recv().await;
            let _ = tx.send(Event::Shutdown).await;
        })
        .detach();
    }

    if !params.publish_only {
        let tx = tx.clone();
        let nav = nav.clone();
        let node = &node;
        let action = params.navigate_action.clone();
        ex.spawn(async move {
            // Asked again every second: a wait resolves on a discovery event, and ros2-client
            // drops such events when many come at once, but a new wait sees a match made.
            let t0 = Instant::now();
            let mut warned = t0;
            loop {
                let found = futures::select! {
                    _ = nav.goal_client().wait_for_service(node).fuse() => true,
                    _ = FutureExt::fuse(smol::Timer::after(Duration::from_secs(1))) => false,
                };
                if found {
                    break;
                }
                if warned.elapsed() >= Duration::from_secs(10) {
                    log::warn!(
                        "no NavigateToPose server on {action} after {} s: is Nav2 running on \
                         this ROS_DOMAIN_ID?",
                        t0.elapsed().as_secs()
                    );
                    warned = Instant::now();
                }
            }
            let _ = tx.send(Event::NavReady).await;
        })
        .detach();
    }

    let t0 = Instant::now();
    let mut state = State {
        params: params.clone(),
        own: own.clone(),
        explorer: Explorer::new(cfg),
        mode: if params.autostart {
            Mode::Exploring
        } else {
            Mode::Idle
        },
        pose: None,
        start: None,
        seq: 0,
        in_flight: Rc::new(RefCell::new(None)),
        goal_task: None,
        cancel_task: None,
        goal_pub,
        markers_pub,
        status_pub,
        nav: nav.clone(),
        mapping,
        map_frame,
        wrong_frame: String::new(),
        tx: tx.clone(),
        t0,
        buf_a: Vec::new(),
        buf_b: Vec::new(),
        last_status: String::new(),
        waiting: None,
        reason: String::new(),
        nav_ready: params.publish_only,
        pending: None,
        sent: None,
        refusals: 0,
        starved_warned: t0,
    };
    // The first status goes out with the first event (a map, a pose, or the first tick
    // after one period), not now: a sample written before discovery has matched anyone
    // reached a Fast DDS 2.9 reader in only about 3 runs of 4, and then nothing after it
    // did either (scripts/ros-interop.sh; ros.md).
    let main = async {
        while let Ok(ev) = rx.recv().await {
            if !state.handle(ev, &ex) {
                break;
            }
        }
        state.shut_down(&ex).await;
        state.mode.clone()
    };
    Ok(smol::block_on(ex.run(main.fuse())))
}

/// The event loop's state.
struct State {
    params: Params,
    /// The node's own topics, resolved.
    own: OwnTopics,
    explorer: Explorer,
    mode: Mode,
    pose: Option<(f64, f64, f64)>,
    start: Option<(f64, f64, f64)>,
    /// Number of the latest goal sent; events of older goals are ignored.
    seq: u64,
    /// The task sending the goal in flight and waiting for its result; dropped (so
    /// cancelled) when another goal replaces it.
    goal_task: Option<smol::Task<()>>,
    /// The task asking Nav2 to cancel the last goal replaced.
    cancel_task: Option<smol::Task<()>>,
    /// The Nav2 id of the goal in flight.
    in_flight: Rc<RefCell<Option<(u64, UUID)>>>,
    goal_pub: ros2_client::Publisher<Ros<PoseStamped>>,
    markers_pub: ros2_client::Publisher<Ros<record::msgs::MarkerArray>>,
    status_pub: ros2_client::Publisher<Text>,
    nav: Rc<NavClient>,
    /// How the action's services are carried (for the message when Nav2 does not answer).
    mapping: ServiceMapping,
    /// The map's frame (see `run`).
    map_frame: Rc<RefCell<String>>,
    /// The last pose frame warned about, so that a pose stream repeats no warning.
    wrong_frame: String,
    tx: async_channel::Sender<Event>,
    t0: Instant,
    buf_a: Vec<(f64, f64)>,
    buf_b: Vec<(f64, f64)>,
    last_status: String,
    /// Why no goal can be chosen just now (the robot is not on the map's free space yet).
    waiting: Option<String>,
    /// Why exploring stopped (empty while it has not).
    reason: String,
    /// Nav2's NavigateToPose server has been discovered (always, in publish-only mode).
    nav_ready: bool,
    /// The goal waiting for Nav2: until its server is discovered, or for the backoff after
    /// it was refused.
    pending: Option<(f64, f64, f64)>,
    /// The goal last sent to Nav2.
    sent: Option<(f64, f64, f64)>,
    /// Goals Nav2 refused or left unanswered in a row.
    refusals: u32,
    /// When the node last warned that no map or pose came (its start at first).
    starved_warned: Instant,
}

impl State {
    fn now_s(&self) -> f64 {
        self.t0.elapsed().as_secs_f64()
    }

    /// `what`, after the reason exploring stopped (if it did).
    fn after(&self, what: &str) -> String {
        if self.reason.is_empty() {
            what.to_string()
        } else {
            format!("{}; {what}", self.reason)
        }
    }

    fn publish_status(&mut self) {
        let mut s = self.mode.status();
        if let (Mode::Exploring, Some(w)) = (&self.mode, &self.waiting) {
            s = format!("waiting: {w}");
        }
        if s != self.last_status {
            log::info!("status: {s}");
            let _ = self.status_pub.publish(Text { data: s.clone() });
            self.last_status = s;
        }
    }

    /// React to one event; false ends the loop.
    fn handle(&mut self, ev: Event, ex: &smol::LocalExecutor<'_>) -> bool {
        match ev {
            Event::Shutdown => return false,
            Event::Map(msg) => match self.explorer.update_map(&msg) {
                Ok(u) => {
                    let frame = frame_name(&msg.header.frame_id);
                    if !frame.is_empty() && *self.map_frame.borrow() != frame {
                        log::info!("map frame: {frame}");
                        *self.map_frame.borrow_mut() = frame.to_string();
                    }
                    log::debug!(
                        "map: {} cells changed{}",
                        u.changed,
                        if u.rebuilt { " (new frame)" } else { "" }
                    );
                    self.check(ex);
                }
                Err(e) => log::warn!("map message skipped: {e}"),
            },
            Event::Pose(x, y, yaw, frame) => {
                let frame = frame_name(&frame);
                if !frame.is_empty() && frame != *self.map_frame.borrow() {
                    if frame != self.wrong_frame {
                        log::warn!(
                            "pose in frame '{frame}', expected the map's frame '{}': skipped \
                             (a localisation pose, such as AMCL's or slam_toolbox's, is in it)",
                            self.map_frame.borrow()
                        );
                        self.wrong_frame = frame.to_string();
                    }
                    return true;
                }
                self.pose = Some((x, y, yaw));
                if self.start.is_none() {
                    self.start = Some((x, y, yaw));
                }
                self.check(ex);
            }
            Event::Tick => {
                self.check(ex);
                self.warn_if_starved();
            }
            Event::Accepted(seq, id) => {
                if seq == self.seq {
                    *self.in_flight.borrow_mut() = Some((seq, id));
                    self.refusals = 0;
                    if self.waiting.as_deref() == Some(&self.nav_waiting()) {
                        self.waiting = None;
                    }
                    // The goal's no-progress time runs from now, not from the decision.
                    let now = self.now_s();
                    self.explorer.restart_progress(now);
                }
            }
            Event::NavReady => {
                log::info!("Nav2's {} server found", self.params.navigate_action);
                self.nav_ready = true;
                if self.waiting.as_deref() == Some(&self.nav_waiting()) {
                    self.waiting = None;
                }
                self.fed();
                if let Some((x, y, yaw)) = self.pending.take()
                    && matches!(self.mode, Mode::Exploring | Mode::Returning)
                {
                    self.send(x, y, yaw, ex);
                }
            }
            Event::Retry(seq) => {
                if seq == self.seq
                    && matches!(self.mode, Mode::Exploring | Mode::Returning)
                    && let Some((x, y, yaw)) = self.pending.take()
                {
                    self.send(x, y, yaw, ex);
                }
            }
            Event::Ended(seq, outcome) => {
                if seq == self.seq {
                    *self.in_flight.borrow_mut() = None;
                    match (&self.mode, outcome) {
                        (
                            Mode::Exploring | Mode::Returning,
                            Outcome::Rejected | Outcome::NoAnswer,
                        ) => self.refused(outcome, ex),
                        (Mode::Returning, Outcome::Succeeded) => {
                            self.mode = Mode::Done(self.after("returned to the start pose"));
                        }
                        (Mode::Returning, _) => {
                            self.mode =
                                Mode::Done(self.after("could not return to the start pose"));
                        }
                        (Mode::Exploring, Outcome::Succeeded) => {
                            self.explorer.goal_reached();
                            self.decide(ex);
                        }
                        (Mode::Exploring, Outcome::Failed) => {
                            log::info!("goal failed: blacklisted");
                            self.explorer.goal_failed();
                            self.decide(ex);
                        }
                        (Mode::Exploring, Outcome::Canceled) => {
                            // Not ours (ours are cancelled under an older seq): an operator
                            // or another node took the robot over. Its goal is not
                            // inaccessible; wait to be told to go on.
                            log::warn!(
                                "goal cancelled by another client: pausing until resume ({} \
                                 true, or {} resume)",
                                self.own.resume,
                                self.own.command
                            );
                            self.explorer.forget_goal();
                            self.mode =
                                Mode::Paused(Some("goal cancelled by another client".into()));
                        }
                        _ => {}
                    }
                }
            }
            Event::Command(c) => self.command(c.trim(), ex),
        }
        self.publish_status();
        true
    }

    fn command(&mut self, c: &str, ex: &smol::LocalExecutor<'_>) {
        match c {
            "start" | "resume" => {
                if matches!(self.mode, Mode::Idle | Mode::Paused(_) | Mode::Done(_)) {
                    self.mode = Mode::Exploring;
                    self.reason.clear();
                    self.decide(ex);
                }
            }
            "stop" => {
                self.cancel_in_flight(ex);
                self.explorer.forget_goal();
                self.mode = Mode::Paused(None);
            }
            "return_to_init" => {
                self.explorer.forget_goal();
                self.return_to_start(ex);
            }
            other => log::warn!(
                "command '{other}' on {} skipped: expected start, stop, resume or \
                 return_to_init",
                self.own.command
            ),
        }
    }

    /// Apply the re-plan policy; decide when it says so.
    fn check(&mut self, ex: &smol::LocalExecutor<'_>) {
        if self.mode != Mode::Exploring {
            return;
        }
        let Some((x, y)) = self.fed() else { return };
        let now = self.now_s();
        if self.pending.is_some() {
            // Nav2 has not taken the goal: the robot cannot be making progress to it.
            self.explorer.restart_progress(now);
        }
        match self.explorer.check(x, y, now) {
            Check::Keep => {}
            Check::NoGoal => {
                if self.in_flight.borrow().is_none() || self.params.publish_only {
                    self.decide(ex)
                }
            }
            why => {
                log::info!("re-plan: {why:?}");
                self.decide(ex)
            }
        }
    }

    /// The robot's position once a map and a pose have come; until then, the status says
    /// which is missing.
    fn fed(&mut self) -> Option<(f64, f64)> {
        if self.explorer.frame().is_none() {
            self.waiting = Some(format!("no map on {}", self.params.map_topic));
            return None;
        }
        let Some((x, y, _)) = self.pose else {
            self.waiting = Some(match self.params.pose_type {
                PoseType::Tf => format!(
                    "no pose from TF ({} in {})",
                    self.params.robot_base_frame,
                    self.map_frame.borrow()
                ),
                _ => format!("no pose on {}", self.params.pose_topic),
            });
            return None;
        };
        Some((x, y))
    }

    fn decide(&mut self, ex: &smol::LocalExecutor<'_>) {
        if self.mode != Mode::Exploring {
            return;
        }
        let Some((x, y)) = self.fed() else { return };
        let now = self.now_s();
        match self.explorer.decide(x, y, now) {
            Decision::Goal(g) => {
                self.waiting = None;
                log::info!("goal ({:.2}, {:.2}), path {:.2} m", g.x, g.y, g.cost_m);
                self.publish_markers();
                self.send(g.x, g.y, g.yaw, ex);
            }
            Decision::Stop(StopReason::NoMap) => {}
            Decision::Stop(
                r @ (StopReason::RobotOffMap { .. } | StopReason::RobotNotOnFreeSpace { .. }),
            ) => {
                // Often passing: the SLAM map does not show the robot's surroundings yet.
                self.waiting = Some(r.to_string());
            }
            Decision::Stop(r) => {
                log::info!("stop: {r}");
                self.publish_markers();
                self.cancel_in_flight(ex);
                self.mode = Mode::Done(r.to_string());
                self.reason = r.to_string();
                if self.params.return_to_init {
                    self.return_to_start(ex);
                }
            }
        }
    }

    fn return_to_start(&mut self, ex: &smol::LocalExecutor<'_>) {
        self.cancel_in_flight(ex);
        match self.start {
            Some((x, y, yaw)) => {
                self.mode = Mode::Returning;
                self.send(x, y, yaw, ex);
                if self.params.publish_only {
                    self.mode = Mode::Done(self.after("start pose published"));
                }
            }
            None => self.mode = Mode::Done(self.after("no start pose known")),
        }
    }

    fn publish_markers(&mut self) {
        if !self.params.visualize {
            return;
        }
        let Some(frame) = self.explorer.frame() else {
            return;
        };
        let res = frame.resolution;
        self.explorer.frontier_points(&mut self.buf_a);
        self.explorer.candidate_points(&mut self.buf_b);
        let header = Header {
            stamp: stamp(Instant::now(), self.t0),
            frame_id: self.map_frame.borrow().clone(),
        };
        let m = markers(&header, &self.buf_a, &self.buf_b, res);
        let _ = self.markers_pub.publish(Ros(m));
    }

    /// Cancel the goal in flight, waiting up to [`SHUTDOWN_CANCEL_WAIT`] for Nav2 to
    /// confirm, and publish the final status.
    async fn shut_down(&mut self, ex: &smol::LocalExecutor<'_>) {
        self.cancel_in_flight(ex);
        if let Some(cancel) = self.cancel_task.take() {
            let answered = futures::select! {
                _ = cancel.fuse() => true,
                _ = FutureExt::fuse(smol::Timer::after(SHUTDOWN_CANCEL_WAIT)) => false,
            };
            if answered {
                log::info!("shutting down: Nav2 answered the goal's cancel request");
            } else {
                log::warn!(
                    "shutting down: no answer from Nav2 to the goal's cancel request in {} s; \
                     the robot may still be driving to it",
                    SHUTDOWN_CANCEL_WAIT.as_secs_f64()
                );
            }
        }
        let s = "shut down".to_string();
        log::info!("status: {s}");
        let _ = self.status_pub.publish(Text { data: s.clone() });
        self.last_status = s;
        // Let the status go out before the participant goes.
        smol::Timer::after(Duration::from_millis(100)).await;
    }

    /// While exploring waits for a first map or pose, say every [`STARVED_WARN_EVERY`] what
    /// it waits for and what would match.
    fn warn_if_starved(&mut self) {
        if self.mode != Mode::Exploring || self.starved_warned.elapsed() < STARVED_WARN_EVERY {
            return;
        }
        let p = &self.params;
        let after = self.t0.elapsed().as_secs();
        let what = if self.explorer.frame().is_none() {
            format!(
                "no map on {} after {after} s: expected nav_msgs/msg/OccupancyGrid from a SLAM \
                 node or map_server, reliable and transient local (a best-effort or volatile \
                 publisher does not match)",
                p.map_topic
            )
        } else if self.pose.is_none() {
            match p.pose_type {
                PoseType::Tf => format!(
                    "no pose from TF after {after} s: expected {} and {} to chain {} up to the \
                     map frame '{}'",
                    self.own.tf,
                    self.own.tf_static,
                    p.robot_base_frame,
                    self.map_frame.borrow()
                ),
                t => format!(
                    "no pose on {} after {after} s: expected geometry_msgs/msg/{} in the map \
                     frame '{}', reliable (a best-effort publisher does not match)",
                    p.pose_topic,
                    if t == PoseType::Stamped {
                        "PoseStamped"
                    } else {
                        "PoseWithCovarianceStamped"
                    },
                    self.map_frame.borrow()
                ),
            }
        } else {
            return;
        };
        log::warn!("{what}");
        self.starved_warned = Instant::now();
    }

    /// The status while a goal waits for Nav2.
    fn nav_waiting(&self) -> String {
        format!(
            "Nav2 ({})",
            self.params.navigate_action.trim_start_matches('/')
        )
    }

    /// Nav2 rejected the goal just sent or left it unanswered: not a sign that the goal is
    /// inaccessible (bt_navigator rejects every goal until it is active), so the same goal
    /// goes again after a backoff.
    fn refused(&mut self, outcome: Outcome, ex: &smol::LocalExecutor<'_>) {
        let Some(goal) = self.sent else { return };
        self.refusals += 1;
        let wait = retry_backoff(self.refusals);
        let why = if outcome == Outcome::Rejected {
            "rejected the goal"
        } else {
            "did not answer the goal request"
        };
        log::warn!(
            "Nav2 {why} ({:.2}, {:.2}), {} in a row: sending it again in {} s (Nav2 rejects \
             goals until its bt_navigator is active)",
            goal.0,
            goal.1,
            self.refusals,
            wait.as_secs()
        );
        self.pending = Some(goal);
        if self.mode == Mode::Exploring {
            self.waiting = Some(self.nav_waiting());
        }
        let seq = self.seq;
        let tx = self.tx.clone();
        ex.spawn(async move {
            smol::Timer::after(wait).await;
            let _ = tx.send(Event::Retry(seq)).await;
        })
        .detach();
    }

    /// Stop following the goal in flight without cancelling it (a new goal preempts it):
    /// its late result is ignored.
    fn drop_in_flight(&mut self) {
        self.seq += 1;
        // A service client of ros2-client takes one call at a time (see cancel_in_flight):
        // the old goal's result request must not eat the new goal's.
        self.goal_task = None;
        *self.in_flight.borrow_mut() = None;
    }

    fn cancel_in_flight(&mut self, ex: &smol::LocalExecutor<'_>) {
        self.seq += 1; // whatever comes back about older goals is ignored
        self.pending = None;
        // Stop waiting for the old goal's answers: a service client of ros2-client takes
        // one call at a time (a call waiting on it drops every other call's reply), so the
        // old goal's result request would eat the next goal's.
        self.goal_task = None;
        if let Some((_, id)) = self.in_flight.borrow_mut().take() {
            let nav = self.nav.clone();
            let cancel = ex.spawn(async move {
                futures::select! {
                    r = nav.async_cancel_goal(id, RosTime::ZERO).fuse() => {
                        if let Err(e) = r {
                            log::warn!("cancel request to Nav2 failed: {e:?}");
                        }
                    }
                    _ = FutureExt::fuse(smol::Timer::after(Duration::from_secs(5))) => {}
                }
            });
            // One cancel request at a time, for the same reason; a newer one replaces it.
            self.cancel_task = Some(cancel);
        }
    }

    /// Publish the goal, and send it to Nav2 unless publish-only.
    fn send(&mut self, x: f64, y: f64, yaw: f64, ex: &smol::LocalExecutor<'_>) {
        let header = Header {
            stamp: stamp(Instant::now(), self.t0),
            frame_id: self.map_frame.borrow().clone(),
        };
        let pose = PoseStamped {
            header,
            pose: Pose::planar(x, y, yaw),
        };
        let _ = self.goal_pub.publish(Ros(pose.clone()));
        if self.params.publish_only {
            return;
        }
        // Nav2 preempts the running goal with the new one; cancelling it first would halt
        // the controller and brake the robot at every re-plan.
        self.drop_in_flight();
        if !self.nav_ready {
            self.pending = Some((x, y, yaw));
            if self.mode == Mode::Exploring {
                self.waiting = Some(self.nav_waiting());
            }
            return;
        }
        self.sent = Some((x, y, yaw));
        let seq = self.seq;
        let nav = self.nav.clone();
        let tx = self.tx.clone();
        let mapping = self.mapping;
        self.goal_task = Some(ex.spawn(async move {
            let goal = Ros(NavigateToPoseGoal {
                pose,
                behavior_tree: String::new(),
            });
            let sent = futures::select! {
                r = nav.async_send_goal(goal).fuse() => r.ok(),
                _ = FutureExt::fuse(smol::Timer::after(GOAL_ANSWER_WAIT)) => None,
            };
            let Some((id, response)) = sent else {
                log::warn!(
                    "no answer from the NavigateToPose server in {} s, over the {mapping:?} \
                     service mapping: is Nav2 running on this ROS_DOMAIN_ID, and on \
                     rmw_cyclonedds_cpp (service_mapping: cyclone) or another RMW \
                     (service_mapping: enhanced)?",
                    GOAL_ANSWER_WAIT.as_secs()
                );
                let _ = tx.send(Event::Ended(seq, Outcome::NoAnswer)).await;
                return;
            };
            if !response.accepted {
                let _ = tx.send(Event::Ended(seq, Outcome::Rejected)).await;
                return;
            }
            let _ = tx.send(Event::Accepted(seq, id)).await;
            let outcome = match nav.async_request_result(id).await {
                Ok((GoalStatusEnum::Succeeded, _)) => Outcome::Succeeded,
                Ok((GoalStatusEnum::Canceled, _)) => Outcome::Canceled,
                Ok(_) | Err(_) => Outcome::Failed,
            };
            let _ = tx.send(Event::Ended(seq, outcome)).await;
        }));
    }
}
