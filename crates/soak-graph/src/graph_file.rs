//! Liquid graphs as files (TOML or JSON, by extension).

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use crate::error::{Element, GraphError, GraphFileError};
use crate::liquid_graph::{LiquidGraph, Node, Pipe};

/// A node as written in a graph file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    /// Name (default `node I`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Position, object space, m.
    pub position: [f64; 3],
    /// Capacity, m³.
    pub capacity: f64,
    /// Liquid at the start, m³.
    #[serde(default)]
    pub liquid: f64,
    /// Vessel height, m (default [`Node::sphere_height`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}

/// A node named by index or by name.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum NodeRef {
    /// 0-based index into `nodes`.
    Index(usize),
    /// A node's `name`.
    Name(String),
}

fn one() -> f64 {
    1.0
}

/// A pipe as written in a graph file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeSpec {
    /// One end.
    pub from: NodeRef,
    /// The other end.
    pub to: NodeRef,
    /// Pipe radius, m.
    pub radius: f64,
    /// Pipe length, m (default: the distance between the nodes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Permeability factor, dimensionless (default 1).
    #[serde(default = "one")]
    pub permeability: f64,
}

/// The contents of a graph file.
///
/// ```toml
/// # Units: metres, cubic metres; positions in the mesh's object space.
/// [[nodes]]
/// name = "bow"                 # optional, default "node I"; unique
/// position = [1.5, 0.35, 0.0]  # m
/// capacity = 0.12              # m³
/// liquid = 0.0                 # m³, optional (default 0)
/// height = 0.5                 # m, optional vessel height (default: diameter of a sphere of the capacity)
///
/// [[edges]]
/// from = "bow"                 # a node name or a 0-based index
/// to = 1
/// radius = 0.02                # m
/// length = 0.8                 # m, optional (default: distance between the nodes)
/// permeability = 1.0           # dimensionless, optional (default 1; 0 closes the pipe)
/// ```
///
/// JSON files have the same keys: `{"nodes": [{...}], "edges": [{...}]}`.
/// Unknown keys, wrong types, unknown node names and invalid values are
/// errors naming the file, the line, and the node or edge.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphFile {
    /// The compartments.
    #[serde(default)]
    pub nodes: Vec<NodeSpec>,
    /// The pipes.
    #[serde(default)]
    pub edges: Vec<EdgeSpec>,
}

/// File formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML (`.toml`).
    Toml,
    /// JSON (`.json`).
    Json,
}

impl Format {
    /// The format of a path, by extension.
    pub fn of(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "toml" => Some(Format::Toml),
            "json" => Some(Format::Json),
            _ => None,
        }
    }
}

impl GraphFile {
    /// The file describing `graph` (every field written out).
    pub fn from_graph(graph: &LiquidGraph) -> Self {
        Self {
            nodes: graph
                .nodes()
                .map(|n| NodeSpec {
                    name: Some(n.name.clone()),
                    position: [n.position.x, n.position.y, n.position.z],
                    capacity: n.capacity,
                    liquid: n.liquid,
                    height: Some(n.height),
                })
                .collect(),
            edges: graph
                .edges()
                .map(|(a, b, p)| EdgeSpec {
                    from: NodeRef::Index(a),
                    to: NodeRef::Index(b),
                    radius: p.radius,
                    length: Some(p.length),
                    permeability: p.permeability,
                })
                .collect(),
        }
    }

    /// Builds the graph; `lines` gives each node's and edge's line for messages.
    fn build(self, path: &Path, lines: &Lines) -> Result<LiquidGraph, GraphFileError> {
        let nodes: Vec<Node> = self
            .nodes
            .into_iter()
            .enumerate()
            .map(|(i, s)| {
                let name = s.name.unwrap_or_else(|| format!("node {i}"));
                let node = Node::new(name, Point3::from(s.position), s.capacity).with_liquid(s.liquid);
                match s.height {
                    Some(h) => node.with_height(h),
                    None => node,
                }
            })
            .collect();
        let mut edges = Vec::with_capacity(self.edges.len());
        for (e, s) in self.edges.into_iter().enumerate() {
            let resolve =
                |r: &NodeRef| -> Result<usize, GraphFileError> {
                    match r {
                        NodeRef::Index(i) if *i < nodes.len() => Ok(*i),
                        NodeRef::Index(i) => Err(GraphFileError::Invalid {
                            path: path.to_path_buf(),
                            line: lines.edge(e),
                            source: GraphError::MissingNode {
                                edge: e,
                                node: *i,
                                nodes: nodes.len(),
                            },
                        }),
                        NodeRef::Name(n) => nodes.iter().position(|x| &x.name == n).ok_or_else(|| {
                            GraphFileError::UnknownNode {
                                path: path.to_path_buf(),
                                line: lines.edge(e),
                                edge: e,
                                name: n.clone(),
                            }
                        }),
                    }
                };
            let (a, b) = (resolve(&s.from)?, resolve(&s.to)?);
            let length = s
                .length
                .unwrap_or_else(|| (nodes[a].position - nodes[b].position).norm());
            edges.push((
                a,
                b,
                Pipe {
                    permeability: s.permeability,
                    radius: s.radius,
                    length,
                },
            ));
        }
        LiquidGraph::new(nodes, edges).map_err(|source| GraphFileError::Invalid {
            path: path.to_path_buf(),
            line: match source.element() {
                Some(Element::Node(i)) => lines.node(i),
                Some(Element::Edge(i)) => lines.edge(i),
                None => 1,
            },
            source,
        })
    }
}

/// 1-based lines of each node and edge in the text.
#[derive(Default)]
struct Lines {
    nodes: Vec<usize>,
    edges: Vec<usize>,
}

impl Lines {
    fn node(&self, i: usize) -> usize {
        self.nodes.get(i).copied().unwrap_or(1)
    }
    fn edge(&self, i: usize) -> usize {
        self.edges.get(i).copied().unwrap_or(1)
    }
}

fn line_at(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

fn toml_lines(text: &str) -> Lines {
    use toml::de::{DeTable, DeValue};
    let Ok(root) = DeTable::parse(text) else {
        return Lines::default();
    };
    let of = |key: &str| -> Vec<usize> {
        match root.get_ref().get(key).map(|v| v.get_ref()) {
            Some(DeValue::Array(a)) => a
                .iter()
                .map(|v| {
                    // The first key of the element's table (array-of-tables
                    // element spans do not point at the element).
                    let start = match v.get_ref() {
                        DeValue::Table(t) => t.iter().map(|(k, _)| k.span().start).min(),
                        _ => None,
                    }
                    .unwrap_or(v.span().start)
                    .min(text.len());
                    if text[..start].trim_end().ends_with('{') {
                        // An inline table.
                        return line_at(text, start);
                    }
                    // An array-of-tables element: the line of its `[[key]]` header.
                    match text[..start].rfind("[[") {
                        Some(h) => line_at(text, h),
                        None => line_at(text, start),
                    }
                })
                .collect(),
            _ => Vec::new(),
        }
    };
    Lines {
        nodes: of("nodes"),
        edges: of("edges"),
    }
}

/// Lines of the elements of the top-level arrays `nodes` and `edges` of a
/// JSON text (a small scanner: serde_json keeps no spans).
fn json_lines(text: &str) -> Lines {
    let mut lines = Lines::default();
    let (mut depth, mut line) = (0usize, 1usize);
    let (mut in_string, mut escape) = (false, false);
    let mut string_start = 0;
    let mut last_string = (0, 0);
    let mut key: Option<&str> = None;
    let mut target: Option<&str> = None;
    let mut expect = false;
    for (i, c) in text.char_indices() {
        if c == '\n' {
            line += 1;
        }
        if in_string {
            if escape {
                escape = false;
            } else if c == '\\' {
                escape = true;
            } else if c == '"' {
                in_string = false;
                last_string = (string_start, i);
            }
            continue;
        }
        if c.is_whitespace() {
            continue;
        }
        if expect && c != ']' {
            match target {
                Some("nodes") => lines.nodes.push(line),
                Some("edges") => lines.edges.push(line),
                _ => {}
            }
        }
        expect = false;
        match c {
            '"' => {
                in_string = true;
                string_start = i + 1;
            }
            ':' if depth == 1 => key = Some(&text[last_string.0..last_string.1]),
            '[' => {
                depth += 1;
                if depth == 2 && matches!(key, Some("nodes") | Some("edges")) {
                    target = key;
                    expect = true;
                }
                key = None;
            }
            '{' => {
                depth += 1;
                key = None;
            }
            ']' | '}' => {
                if c == ']' && depth == 2 {
                    target = None;
                }
                depth = depth.saturating_sub(1);
            }
            ',' if depth == 2 && target.is_some() => expect = true,
            _ => {}
        }
    }
    lines
}

/// Parses a graph from text in `format`; `path` names it in messages.
///
/// # Errors
/// [`GraphFileError::Parse`] with the line for bad syntax or schema, then
/// the first invalid node or edge with its line.
pub fn parse_graph(text: &str, format: Format, path: &Path) -> Result<LiquidGraph, GraphFileError> {
    let (file, lines) = match format {
        Format::Toml => {
            let file: GraphFile = toml::from_str(text).map_err(|e| GraphFileError::Parse {
                path: path.to_path_buf(),
                line: e.span().map_or(1, |s| line_at(text, s.start)),
                message: e.message().trim_end().to_string(),
            })?;
            (file, toml_lines(text))
        }
        Format::Json => {
            let file: GraphFile = serde_json::from_str(text).map_err(|e| GraphFileError::Parse {
                path: path.to_path_buf(),
                line: e.line().max(1),
                message: e.to_string(),
            })?;
            (file, json_lines(text))
        }
    };
    file.build(path, &lines)
}

/// Reads a graph file (`.toml` or `.json`).
///
/// # Errors
/// See [`parse_graph`]; also unreadable files and unknown extensions.
///
/// # Example
/// ```
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/graphs/fig4_5_barrier.toml");
/// let graph = soak_graph::load_graph(path)?;
/// assert_eq!(graph.node_count(), 3);
/// # Ok::<(), soak_graph::GraphFileError>(())
/// ```
pub fn load_graph(path: impl AsRef<Path>) -> Result<LiquidGraph, GraphFileError> {
    let path = path.as_ref();
    let format = Format::of(path).ok_or_else(|| GraphFileError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    let text = std::fs::read_to_string(path).map_err(|source| GraphFileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_graph(&text, format, path)
}

/// Writes `graph` as TOML text.
pub fn to_toml(graph: &LiquidGraph) -> String {
    toml::to_string(&GraphFile::from_graph(graph)).unwrap_or_default()
}

/// Writes `graph` as pretty JSON text.
pub fn to_json(graph: &LiquidGraph) -> String {
    serde_json::to_string_pretty(&GraphFile::from_graph(graph)).unwrap_or_default()
}

/// A path for messages when parsing text that has no file.
pub fn unnamed() -> PathBuf {
    PathBuf::from("<text>")
}
