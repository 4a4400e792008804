//! ROS 2 names as rcl resolves them: the node's name and namespace, relative and private
//! names expanded to fully qualified ones, and the static remapping rules of `--ros-args -r`.
//!
//! A rule is `[NODE:]FROM:=TO` (design.ros2.org, "Remapping Names"; rcl's `rcl_remap_*`):
//!
//! - `__node:=NAME` (or `__name:=NAME`) renames the node, `__ns:=/NS` puts it in a
//!   namespace;
//! - any other rule remaps a name: `FROM` and `TO` are expanded to fully qualified names in
//!   the node's namespace (`map` in `/robot1` is `/robot1/map`, `~/x` is
//!   `/robot1/NODE/x`), and a name the node uses is replaced by `TO` when its fully
//!   qualified form is `FROM`'s. `rostopic://FROM:=TO` applies to topics (and, as rcl does
//!   since Jazzy, action names) only, `rosservice://FROM:=TO` to services only;
//! - a `NODE:` prefix limits the rule to the node of that name: its name before `__node`
//!   rules for a `__node` rule, after them for any other;
//! - the first rule that matches wins, in the order given.
//!
//! As in rcl, the wildcards `*` and `**` and the back-references `\1`…`\9` of the design
//! are not implemented; a rule with one is refused.

// The node's own topics are relative, as explore_lite's are: in the node's namespace
// (`/robot1/explore/status` under `__ns:=/robot1`), `/explore/status` in the root one.

/// The node's resume topic (explore_lite's).
pub const RESUME_TOPIC: &str = "explore/resume";
/// The node's command topic.
pub const COMMAND_TOPIC: &str = "explore/command";
/// The node's status topic.
pub const STATUS_TOPIC: &str = "explore/status";
/// The default of `goal_topic`.
pub const GOAL_TOPIC: &str = "explore/goal";
/// The default of `markers_topic` (explore_lite's name).
pub const MARKERS_TOPIC: &str = "explore/frontiers";
/// TF, with `pose_type: tf` (absolute, as tf2_ros's listener names it).
pub const TF_TOPIC: &str = "/tf";
/// Static TF, with `pose_type: tf`.
pub const TF_STATIC_TOPIC: &str = "/tf_static";

/// What a ROS 2 name is made of, for error messages.
pub const NAME_FORM: &str = "letters, digits and '_' between '/'";

/// What a node's name is made of, for error messages.
const NODE_NAME_FORM: &str = "one token: letters, digits and '_'";

/// One `-r` rule, as given and as understood.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Remap {
    /// The rule as given (`robot1_explore:map:=/slam/map`).
    pub rule: String,
    /// The node it is for (`NODE:` prefix); `None`: every node.
    pub node: Option<String>,
    /// What it does.
    pub kind: RemapKind,
}

/// What a rule does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RemapKind {
    /// `__node:=NAME`: the node's name.
    NodeName(String),
    /// `__ns:=/NS`: the node's namespace (absolute, without a trailing `/` but for `/`).
    Namespace(String),
    /// `FROM:=TO`: a name (not yet expanded: `map`, `~/x`, `/map`).
    Name {
        /// The name matched.
        from: String,
        /// Its replacement.
        to: String,
        /// Applies to topic (and action) names.
        topics: bool,
        /// Applies to service names.
        services: bool,
    },
}

/// A token (the text between two `/`), as rcl's lexer takes it: letters, digits and `_`,
/// not starting with a digit, without `__`. The reason when it is not one.
fn token_problem(t: &str) -> Option<String> {
    if t.is_empty() {
        return Some("an empty token (a '/' at the end, or '//')".into());
    }
    if let Some(c) = t
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_'))
    {
        return Some(match c {
            '*' => "the wildcards '*' and '**', which ROS 2 does not implement either".into(),
            '\\' => "a back-reference ('\\1'…'\\9'), which ROS 2 does not implement either".into(),
            '~' => "'~' other than as '~' or '~/…' at the start".into(),
            c => format!("the character {c:?}"),
        });
    }
    if t.starts_with(|c: char| c.is_ascii_digit()) {
        return Some(format!("a token starting with a digit ('{t}')"));
    }
    if t.contains("__") {
        return Some(format!("'__' in a token ('{t}')"));
    }
    None
}

/// A node's name: one token.
fn node_name_problem(name: &str) -> Option<String> {
    if name.is_empty() {
        return Some("nothing".into());
    }
    if name.contains('/') {
        return Some("a '/' (a node's name is one token; the namespace is __ns)".into());
    }
    token_problem(name)
}

/// `name` checked as a rule's side takes it (rcl's grammar: `/` or `~/` or nothing, then
/// tokens between single `/`).
fn rule_name_problem(name: &str) -> Option<String> {
    if name.is_empty() {
        return Some("nothing".into());
    }
    let rest = name
        .strip_prefix("~/")
        .or_else(|| name.strip_prefix('/'))
        .unwrap_or(name);
    if name == "~" {
        return Some("'~' alone (a rule names the private namespace as '~/NAME')".into());
    }
    if rest.contains('{') || rest.contains('}') {
        return Some("a substitution ('{node}', '{ns}'), which rules do not take".into());
    }
    rest.split('/').find_map(token_problem)
}

/// An absolute namespace (`/`, `/robot1`, `/a/b`; one trailing `/` is dropped, as rcl's
/// grammar allows it), or why `ns` is not one.
pub fn namespace(ns: &str) -> Result<String, String> {
    let expected =
        || format!("expected an absolute namespace ('/' or '/NAME/…', {NAME_FORM}), found '{ns}'");
    let Some(rest) = ns.strip_prefix('/') else {
        return Err(expected());
    };
    let rest = rest.strip_suffix('/').unwrap_or(rest);
    if rest.is_empty() {
        return Ok("/".into());
    }
    match rest.split('/').find_map(token_problem) {
        Some(why) => Err(format!("{} ({why})", expected())),
        None => Ok(format!("/{rest}")),
    }
}

/// Parse one rule of `-r` / `--remap`; the error says what was expected and what was found
/// (the caller names the rule).
pub fn parse_remap(rule: &str) -> Result<Remap, String> {
    let Some((left, to)) = rule.split_once(":=") else {
        return Err(format!(
            "expected a remapping rule FROM:=TO (or __node:=NAME, __ns:=/NAMESPACE), found \
             '{rule}' without ':='"
        ));
    };
    // An optional `NODE:` prefix; `rostopic://` and `rosservice://` are not one.
    let url = |s: &str| s.starts_with("rostopic://") || s.starts_with("rosservice://");
    let (node, from) = match left.split_once(':') {
        Some((n, rest)) if !url(left) => {
            if let Some(why) = node_name_problem(n) {
                return Err(format!(
                    "expected a node's name before ':' in NODE:FROM:=TO ({NODE_NAME_FORM}), \
                     found '{n}' ({why})"
                ));
            }
            (Some(n.to_string()), rest)
        }
        _ => (None, left),
    };
    let kind = match from {
        "__node" | "__name" => {
            if let Some(why) = node_name_problem(to) {
                return Err(format!(
                    "expected a node name after '{from}:=' ({NODE_NAME_FORM}), found '{to}' \
                     ({why})"
                ));
            }
            RemapKind::NodeName(to.to_string())
        }
        "__ns" => RemapKind::Namespace(namespace(to).map_err(|e| format!("after '__ns:=': {e}"))?),
        _ => {
            let (from, topics, services) = if let Some(f) = from.strip_prefix("rostopic://") {
                (f, true, false)
            } else if let Some(f) = from.strip_prefix("rosservice://") {
                (f, false, true)
            } else {
                (from, true, true)
            };
            if let Some(why) = rule_name_problem(from) {
                return Err(format!(
                    "expected a name before ':=' ('/…', '~/…' or relative; {NAME_FORM}), \
                     found '{from}' ({why})"
                ));
            }
            if let Some(why) = rule_name_problem(to) {
                return Err(format!(
                    "expected a name after ':=' ('/…', '~/…' or relative; {NAME_FORM}), found \
                     '{to}' ({why})"
                ));
            }
            RemapKind::Name {
                from: from.to_string(),
                to: to.to_string(),
                topics,
                services,
            }
        }
    };
    Ok(Remap {
        rule: rule.to_string(),
        node,
        kind,
    })
}

/// The node's name and namespace after the `__node` and `__ns` rules, and the name rules
/// that apply to it: resolves every name the node uses as rcl does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NameResolver {
    node: String,
    namespace: String,
    rules: Vec<Remap>,
}

impl NameResolver {
    /// The resolver of node `node` (its name in code, `--node`) in the root namespace, with
    /// `rules` in the order given. The first `__node` rule for the node (by that name)
    /// renames it; the first `__ns` rule for it (by its new name) sets its namespace; the
    /// name rules for it, in order, are kept.
    pub fn new(node: &str, rules: &[Remap]) -> Result<Self, String> {
        if let Some(why) = node_name_problem(node) {
            return Err(format!(
                "expected a node name ({NODE_NAME_FORM}), found '{node}' ({why})"
            ));
        }
        let for_node = |r: &&Remap, name: &str| r.node.as_deref().is_none_or(|n| n == name);
        let name = rules
            .iter()
            .filter(|r| for_node(r, node))
            .find_map(|r| match &r.kind {
                RemapKind::NodeName(n) => Some(n.clone()),
                _ => None,
            })
            .unwrap_or_else(|| node.to_string());
        let namespace = rules
            .iter()
            .filter(|r| for_node(r, &name))
            .find_map(|r| match &r.kind {
                RemapKind::Namespace(ns) => Some(ns.clone()),
                _ => None,
            })
            .unwrap_or_else(|| "/".to_string());
        let rules = rules
            .iter()
            .filter(|r| for_node(r, &name) && matches!(r.kind, RemapKind::Name { .. }))
            .cloned()
            .collect();
        Ok(Self {
            node: name,
            namespace,
            rules,
        })
    }

    /// The node's name (after `__node`).
    pub fn node(&self) -> &str {
        &self.node
    }

    /// The node's namespace (after `__ns`): `/` or `/a/b`.
    pub fn namespace(&self) -> &str {
        &self.namespace
    }

    /// `/NS/NODE` (`/NODE` in the root namespace).
    pub fn fully_qualified_node_name(&self) -> String {
        format!("{}/{}", self.ns_prefix(), self.node)
    }

    /// The namespace as a prefix: "" for the root, `/a/b` otherwise.
    fn ns_prefix(&self) -> &str {
        self.namespace.trim_end_matches('/')
    }

    /// `name` as a fully qualified name, as rcl expands it: absolute names as they are,
    /// relative ones in the namespace, `~` the node's own (`/NS/NODE`), and the
    /// substitutions `{node}`, `{ns}` and `{namespace}`. The error is why it is not a
    /// ROS 2 name.
    pub fn expand(&self, name: &str) -> Result<String, String> {
        if name.is_empty() {
            return Err("an empty name".into());
        }
        let mut s = String::with_capacity(name.len() + 16);
        let mut rest = name;
        while let Some(open) = rest.find('{') {
            let Some(len) = rest[open..].find('}') else {
                return Err("a '{' without its '}'".into());
            };
            s.push_str(&rest[..open]);
            match &rest[open + 1..open + len] {
                "node" => s.push_str(&self.node),
                "ns" | "namespace" => s.push_str(self.ns_prefix()),
                other => {
                    return Err(format!(
                        "the substitution '{{{other}}}' (known: {{node}}, {{ns}}, {{namespace}})"
                    ));
                }
            }
            rest = &rest[open + len + 1..];
        }
        s.push_str(rest);
        if s.contains('}') {
            return Err("a '}' without its '{'".into());
        }
        let full = if s == "~" {
            self.fully_qualified_node_name()
        } else if let Some(r) = s.strip_prefix("~/") {
            format!("{}/{r}", self.fully_qualified_node_name())
        } else if s.starts_with('/') {
            s
        } else {
            format!("{}/{s}", self.ns_prefix())
        };
        match full[1..].split('/').find_map(token_problem) {
            Some(why) => Err(why),
            None => Ok(full),
        }
    }

    /// The first name rule for topics whose `FROM` expands to `expanded`.
    fn topic_rule(&self, expanded: &str) -> Option<(&Remap, &str)> {
        self.rules.iter().find_map(|r| match &r.kind {
            RemapKind::Name {
                from, to, topics, ..
            } if *topics && self.expand(from).is_ok_and(|f| f == expanded) => {
                Some((r, to.as_str()))
            }
            _ => None,
        })
    }

    /// The fully qualified name of topic (or action) `name` after the remapping rules:
    /// expanded, then replaced by the first rule that matches, whose `TO` is expanded too.
    pub fn resolve(&self, name: &str) -> Result<String, String> {
        let expanded = self.expand(name)?;
        match self.topic_rule(&expanded) {
            Some((_, to)) => self.expand(to),
            None => Ok(expanded),
        }
    }

    /// The rules for this node that match none of the topic names `names` (as the node
    /// uses them, before remapping): they remap nothing, often a misspelt name.
    pub fn unused_rules(&self, names: &[&str]) -> Vec<&str> {
        let expanded: Vec<String> = names.iter().filter_map(|n| self.expand(n).ok()).collect();
        self.rules
            .iter()
            .filter(|r| {
                !expanded
                    .iter()
                    .any(|e| self.topic_rule(e).is_some_and(|(m, _)| std::ptr::eq(m, *r)))
            })
            .map(|r| r.rule.as_str())
            .collect()
    }

    /// The fully qualified names of the node's own topics, after the rules.
    pub fn own_topics(&self) -> Result<OwnTopics, String> {
        let r = |n: &str| self.resolve(n).map_err(|e| format!("{n}: {e}"));
        Ok(OwnTopics {
            resume: r(RESUME_TOPIC)?,
            command: r(COMMAND_TOPIC)?,
            status: r(STATUS_TOPIC)?,
            tf: r(TF_TOPIC)?,
            tf_static: r(TF_STATIC_TOPIC)?,
        })
    }
}

/// The names of the topics the node uses that are not parameters, fully qualified.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OwnTopics {
    /// [`RESUME_TOPIC`] resolved.
    pub resume: String,
    /// [`COMMAND_TOPIC`] resolved.
    pub command: String,
    /// [`STATUS_TOPIC`] resolved.
    pub status: String,
    /// [`TF_TOPIC`] resolved.
    pub tf: String,
    /// [`TF_STATIC_TOPIC`] resolved.
    pub tf_static: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rules(rs: &[&str]) -> Vec<Remap> {
        rs.iter().map(|r| parse_remap(r).unwrap()).collect()
    }

    fn resolver(node: &str, rs: &[&str]) -> NameResolver {
        NameResolver::new(node, &rules(rs)).unwrap()
    }

    #[test]
    fn rules_parse_into_their_parts() {
        let r = parse_remap("map:=/slam/map").unwrap();
        assert_eq!(r.node, None);
        assert_eq!(
            r.kind,
            RemapKind::Name {
                from: "map".into(),
                to: "/slam/map".into(),
                topics: true,
                services: true
            }
        );
        let r = parse_remap("explorer:~/status:=/status").unwrap();
        assert_eq!(r.node.as_deref(), Some("explorer"));
        assert!(matches!(r.kind, RemapKind::Name { ref from, .. } if from == "~/status"));
        let r = parse_remap("rostopic:///map:=map2").unwrap();
        assert!(matches!(
            r.kind,
            RemapKind::Name {
                topics: true,
                services: false,
                ..
            }
        ));
        let r = parse_remap("n:rosservice://a:=b").unwrap();
        assert_eq!(r.node.as_deref(), Some("n"));
        assert!(matches!(
            r.kind,
            RemapKind::Name {
                topics: false,
                services: true,
                ..
            }
        ));
        assert_eq!(
            parse_remap("__node:=x").unwrap().kind,
            RemapKind::NodeName("x".into())
        );
        assert_eq!(
            parse_remap("__name:=x").unwrap().kind,
            RemapKind::NodeName("x".into())
        );
        assert_eq!(
            parse_remap("a:__ns:=/r1/").unwrap(),
            Remap {
                rule: "a:__ns:=/r1/".into(),
                node: Some("a".into()),
                kind: RemapKind::Namespace("/r1".into())
            }
        );
        assert_eq!(
            parse_remap("__ns:=/").unwrap().kind,
            RemapKind::Namespace("/".into())
        );
    }

    #[test]
    fn a_bad_rule_says_what_was_expected_and_found() {
        let e = parse_remap("map").unwrap_err();
        assert_eq!(
            e,
            "expected a remapping rule FROM:=TO (or __node:=NAME, __ns:=/NAMESPACE), found \
             'map' without ':='"
        );
        let e = parse_remap(":=/x").unwrap_err();
        assert!(e.starts_with("expected a name before ':='"), "{e}");
        assert!(e.ends_with("found '' (nothing)"), "{e}");
        let e = parse_remap("map:=").unwrap_err();
        assert!(e.starts_with("expected a name after ':='"), "{e}");
        assert!(e.ends_with("found '' (nothing)"), "{e}");
        let e = parse_remap("map:=a b").unwrap_err();
        assert!(e.ends_with("found 'a b' (the character ' ')"), "{e}");
        let e = parse_remap("/map/:=x").unwrap_err();
        assert!(e.contains("an empty token"), "{e}");
        let e = parse_remap("map:=/2d/map").unwrap_err();
        assert!(e.contains("a token starting with a digit ('2d')"), "{e}");
        let e = parse_remap("a__b:=x").unwrap_err();
        assert!(e.contains("'__' in a token"), "{e}");
        let e = parse_remap("**/map:=x").unwrap_err();
        assert!(e.contains("wildcards"), "{e}");
        let e = parse_remap("/x/*:=\\1/y").unwrap_err();
        assert!(e.contains("wildcards"), "{e}");
        let e = parse_remap("x:=\\1/y").unwrap_err();
        assert!(e.contains("back-reference"), "{e}");
        let e = parse_remap("~:=x").unwrap_err();
        assert!(e.contains("'~' alone"), "{e}");
        let e = parse_remap("{node}/x:=y").unwrap_err();
        assert!(e.contains("substitution"), "{e}");
        let e = parse_remap("__ns:=robot1").unwrap_err();
        assert_eq!(
            e,
            "after '__ns:=': expected an absolute namespace ('/' or '/NAME/…', letters, \
             digits and '_' between '/'), found 'robot1'"
        );
        let e = parse_remap("__ns:=/a//b").unwrap_err();
        assert!(e.contains("an empty token"), "{e}");
        let e = parse_remap("__node:=a/b").unwrap_err();
        assert!(
            e.starts_with("expected a node name after '__node:='"),
            "{e}"
        );
        assert!(e.contains("found 'a/b'"), "{e}");
        let e = parse_remap("__node:=").unwrap_err();
        assert!(e.ends_with("found '' (nothing)"), "{e}");
        let e = parse_remap("my node:map:=x").unwrap_err();
        assert!(e.starts_with("expected a node's name before ':'"), "{e}");
        assert!(e.contains("found 'my node'"), "{e}");
    }

    #[test]
    fn names_expand_in_the_namespace_and_the_private_namespace() {
        let r = resolver("explorer", &["__ns:=/robot1"]);
        assert_eq!(r.namespace(), "/robot1");
        assert_eq!(r.fully_qualified_node_name(), "/robot1/explorer");
        assert_eq!(r.expand("map").unwrap(), "/robot1/map");
        assert_eq!(r.expand("/map").unwrap(), "/map");
        assert_eq!(r.expand("a/b").unwrap(), "/robot1/a/b");
        assert_eq!(r.expand("~").unwrap(), "/robot1/explorer");
        assert_eq!(r.expand("~/goal").unwrap(), "/robot1/explorer/goal");
        assert_eq!(r.expand("{node}/x").unwrap(), "/robot1/explorer/x");
        assert_eq!(r.expand("{ns}/x").unwrap(), "/robot1/x");
        assert_eq!(
            r.expand("/{namespace}/x").unwrap_err(),
            "an empty token (a '/' at the end, or '//')"
        );
        let root = resolver("explorer", &[]);
        assert_eq!(root.namespace(), "/");
        assert_eq!(root.fully_qualified_node_name(), "/explorer");
        assert_eq!(root.expand("map").unwrap(), "/map");
        assert_eq!(root.expand("~/goal").unwrap(), "/explorer/goal");
        assert_eq!(root.expand("{ns}/x").unwrap(), "/x");
        for (bad, why) in [
            ("", "an empty name"),
            ("ns/~map", "'~' other than as '~' or '~/…' at the start"),
            ("~map", "'~' other than as '~' or '~/…' at the start"),
            ("map/", "an empty token (a '/' at the end, or '//')"),
            ("a b", "the character ' '"),
            (
                "{robot}/x",
                "the substitution '{robot}' (known: {node}, {ns}, {namespace})",
            ),
            ("{node/x", "a '{' without its '}'"),
        ] {
            assert_eq!(root.expand(bad).unwrap_err(), why, "{bad}");
        }
    }

    #[test]
    fn node_and_namespace_rules_follow_rcl() {
        // The first __node rule wins; a prefixed one matches the name in code.
        let r = resolver("explorer", &["__node:=a", "__node:=b"]);
        assert_eq!(r.node(), "a");
        let r = resolver("explorer", &["other:__node:=a", "explorer:__node:=b"]);
        assert_eq!(r.node(), "b");
        // A prefixed __ns rule matches the node's new name.
        let r = resolver(
            "explorer",
            &["__node:=b", "explorer:__ns:=/x", "b:__ns:=/y"],
        );
        assert_eq!((r.node(), r.namespace()), ("b", "/y"));
        let r = resolver("explorer", &["other:__ns:=/x"]);
        assert_eq!(r.namespace(), "/");
        assert!(NameResolver::new("my node", &[]).is_err());
        assert!(NameResolver::new("a__b", &[]).is_err());
    }

    #[test]
    fn a_remapped_name_is_the_first_matching_rules_replacement() {
        // Exact FQN match.
        let r = resolver("explorer", &["/map:=/slam/map"]);
        assert_eq!(r.resolve("/map").unwrap(), "/slam/map");
        assert_eq!(r.resolve("map").unwrap(), "/slam/map");
        assert_eq!(r.resolve("/mapper").unwrap(), "/mapper");
        assert_eq!(r.resolve("/map/x").unwrap(), "/map/x");
        // Both sides of a relative rule expand in the namespace.
        let r = resolver("explorer", &["__ns:=/r1", "map:=slam_map"]);
        assert_eq!(r.resolve("map").unwrap(), "/r1/slam_map");
        assert_eq!(r.resolve("/r1/map").unwrap(), "/r1/slam_map");
        assert_eq!(r.resolve("/map").unwrap(), "/map");
        // Private names.
        let r = resolver("explorer", &["__ns:=/r1", "~/goal:=/goals"]);
        assert_eq!(r.resolve("~/goal").unwrap(), "/goals");
        assert_eq!(r.resolve("/r1/explorer/goal").unwrap(), "/goals");
        let r = resolver("explorer", &["/status:=~/status"]);
        assert_eq!(r.resolve("/status").unwrap(), "/explorer/status");
        // The first match wins, and a replacement is not remapped again.
        let r = resolver("explorer", &["foo:=bar", "bar:=baz", "foo:=qux"]);
        assert_eq!(r.resolve("foo").unwrap(), "/bar");
        assert_eq!(r.resolve("bar").unwrap(), "/baz");
        // A rule for another node is not this node's.
        let r = resolver("explorer", &["other:map:=/x", "explorer:map:=/y"]);
        assert_eq!(r.resolve("map").unwrap(), "/y");
        let r = resolver("explorer", &["other:map:=/x"]);
        assert_eq!(r.resolve("map").unwrap(), "/map");
        // ... by its name after __node.
        let r = resolver(
            "explorer",
            &["__node:=e2", "explorer:map:=/x", "e2:map:=/y"],
        );
        assert_eq!(r.resolve("map").unwrap(), "/y");
        // Service-only rules leave topics alone; topic-only ones apply.
        let r = resolver("explorer", &["rosservice://map:=/x"]);
        assert_eq!(r.resolve("map").unwrap(), "/map");
        let r = resolver("explorer", &["rostopic://map:=/x"]);
        assert_eq!(r.resolve("map").unwrap(), "/x");
    }

    #[test]
    fn the_nodes_own_topics_follow_the_namespace_and_the_rules() {
        let root = resolver("frontier_explore", &[]).own_topics().unwrap();
        assert_eq!(
            root,
            OwnTopics {
                resume: "/explore/resume".into(),
                command: "/explore/command".into(),
                status: "/explore/status".into(),
                tf: "/tf".into(),
                tf_static: "/tf_static".into(),
            }
        );
        let r = resolver(
            "frontier_explore",
            &[
                "__ns:=/robot1",
                "/tf:=tf",
                "/tf_static:=tf_static",
                "explore/status:=status",
                "explore/command:=~/command",
            ],
        );
        let t = r.own_topics().unwrap();
        assert_eq!(t.resume, "/robot1/explore/resume");
        assert_eq!(t.command, "/robot1/frontier_explore/command");
        assert_eq!(t.status, "/robot1/status");
        assert_eq!(
            (t.tf.as_str(), t.tf_static.as_str()),
            ("/robot1/tf", "/robot1/tf_static")
        );
    }

    #[test]
    fn rules_that_match_no_name_are_listed() {
        let r = resolver("n", &["/mapp:=/x", "map:=/y", "other:/pose:=/z", "__ns:=/"]);
        assert_eq!(r.unused_rules(&["/map", "/pose"]), vec!["/mapp:=/x"]);
        // A rule shadowed by an earlier one for the same name is unused too.
        let r = resolver("n", &["map:=/a", "/map:=/b"]);
        assert_eq!(r.unused_rules(&["map"]), vec!["/map:=/b"]);
    }
}
