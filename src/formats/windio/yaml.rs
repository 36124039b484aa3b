//! Walking a parsed YAML document with the path and line of every node, so that each error can
//! say where it is: `file:line: components.blade.chord.grid[4]: expected …`.
//!
//! Anchors and aliases are resolved by the parser (an alias is a copy of the anchored node, and
//! its lines are those of the anchor, where the data is written). The parser caps how many nodes
//! aliases may expand to, so a file of nested aliases cannot exhaust memory.

use crate::error::{Error, Result};
use saphyr::{LoadableYamlNode, MarkedYaml, Scalar, YamlData};

/// The parsed document of a file.
pub(super) struct Document<'y> {
    root: MarkedYaml<'y>,
}

impl<'y> Document<'y> {
    /// The first document of `text`; a YAML syntax error names its line.
    pub(super) fn parse(text: &'y str, file: &str) -> Result<Document<'y>> {
        let mut docs = MarkedYaml::load_from_str(text).map_err(|e| {
            Error::format(
                file,
                e.marker().line(),
                format!("not valid YAML: {}", e.info()),
            )
        })?;
        if docs.is_empty() {
            return Err(Error::format(
                file,
                0,
                "empty: expected a WindIO ontology (a mapping with components, airfoils, materials and assembly)",
            ));
        }
        Ok(Document {
            root: docs.swap_remove(0),
        })
    }

    pub(super) fn root<'a>(&'a self, file: &'a str) -> Node<'a, 'y> {
        Node {
            y: &self.root,
            path: String::new(),
            file,
        }
    }
}

/// A node with its path from the document root and the file it came from.
#[derive(Clone)]
pub(super) struct Node<'a, 'y> {
    y: &'a MarkedYaml<'y>,
    pub(super) path: String,
    file: &'a str,
}

impl<'a, 'y> Node<'a, 'y> {
    /// The 1-based line where the node starts.
    pub(super) fn line(&self) -> usize {
        self.y.span.start.line()
    }

    /// An error at this node: its line, its path and what was expected.
    pub(super) fn error(&self, message: impl AsRef<str>) -> Error {
        let place = if self.path.is_empty() {
            "the document".to_string()
        } else {
            self.path.clone()
        };
        Error::format(
            self.file,
            self.line(),
            format!("{place}: {}", message.as_ref()),
        )
    }

    fn data(&self) -> &'a YamlData<'y, MarkedYaml<'y>> {
        let mut data = &self.y.data;
        while let YamlData::Tagged(_, inner) = data {
            data = &inner.data;
        }
        data
    }

    fn child_path(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    fn describe(&self) -> String {
        match self.data() {
            YamlData::Sequence(s) => format!("a list of {} items", s.len()),
            YamlData::Mapping(_) => "a mapping".to_string(),
            YamlData::Value(Scalar::Null) => "nothing (null)".to_string(),
            YamlData::Value(Scalar::Boolean(b)) => format!("the boolean {b}"),
            YamlData::Value(Scalar::Integer(i)) => format!("the number {i}"),
            YamlData::Value(Scalar::FloatingPoint(f)) => format!("the number {f}"),
            YamlData::Value(Scalar::String(s)) => format!("the text `{}`", clip(s)),
            YamlData::Representation(s, _, _) => format!("`{}`", clip(s)),
            _ => "an unreadable value".to_string(),
        }
    }

    fn expect_mapping(&self) -> Result<()> {
        match self.data() {
            YamlData::Mapping(_) => Ok(()),
            _ => Err(self.error(format!("expected a mapping, found {}", self.describe()))),
        }
    }

    /// The value of `key` if this node is a mapping that has it (a null value counts as absent,
    /// as `key:` with nothing after it says nothing).
    pub(super) fn get(&self, key: &str) -> Result<Option<Node<'a, 'y>>> {
        self.expect_mapping()?;
        let found = self.data().as_mapping_get(key).map(|y| Node {
            y,
            path: self.child_path(key),
            file: self.file,
        });
        Ok(found.filter(|n| !matches!(n.data(), YamlData::Value(Scalar::Null))))
    }

    /// The value of a required `key`; its absence is an error at this node naming the key's path.
    pub(super) fn req(&self, key: &str, what: &str) -> Result<Node<'a, 'y>> {
        self.get(key)?.ok_or_else(|| self.missing(key, what))
    }

    /// The error for a required `key` this mapping lacks, at the mapping's line.
    pub(super) fn missing(&self, key: &str, what: &str) -> Error {
        Error::format(
            self.file,
            self.line(),
            format!("{}: missing; expected {what}", self.child_path(key)),
        )
    }

    /// The items of a list.
    pub(super) fn items(&self) -> Result<Vec<Node<'a, 'y>>> {
        match self.data() {
            YamlData::Sequence(s) => Ok(s
                .iter()
                .enumerate()
                .map(|(i, y)| Node {
                    y,
                    path: format!("{}[{i}]", self.path),
                    file: self.file,
                })
                .collect()),
            _ => Err(self.error(format!("expected a list, found {}", self.describe()))),
        }
    }

    /// A finite number.
    pub(super) fn number(&self) -> Result<f64> {
        let v = match self.data() {
            YamlData::Value(Scalar::Integer(i)) => *i as f64,
            YamlData::Value(Scalar::FloatingPoint(f)) => f.into_inner(),
            _ => {
                return Err(self.error(format!("expected a number, found {}", self.describe())));
            }
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(format!("expected a finite number, found {v}")))
        }
    }

    /// A list of finite numbers.
    pub(super) fn numbers(&self) -> Result<Vec<f64>> {
        self.items()?.iter().map(Node::number).collect()
    }

    /// A text value. Plain scalars that YAML reads as numbers or booleans (an airfoil named
    /// `1`, a web named `yes`) are taken as written.
    pub(super) fn text(&self) -> Result<String> {
        match self.data() {
            YamlData::Value(Scalar::String(s)) => Ok(s.to_string()),
            YamlData::Value(Scalar::Integer(i)) => Ok(i.to_string()),
            YamlData::Value(Scalar::FloatingPoint(f)) => Ok(f.to_string()),
            YamlData::Value(Scalar::Boolean(b)) => Ok(b.to_string()),
            _ => Err(self.error(format!("expected a name, found {}", self.describe()))),
        }
    }

    /// A list of text values.
    pub(super) fn texts(&self) -> Result<Vec<String>> {
        self.items()?.iter().map(Node::text).collect()
    }
}

fn clip(s: &str) -> String {
    const MAX: usize = 40;
    if s.chars().count() > MAX {
        format!("{}…", s.chars().take(MAX).collect::<String>())
    } else {
        s.to_string()
    }
}
