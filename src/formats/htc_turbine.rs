//! The turbine an htc model describes around its blades (docs/model.md §13.7): the main bodies
//! with their `c2_def`, `timoschenko_input`, damping and `concentrated_mass`es, how the
//! `orientation` block places them (`base`, `relative` with their `mbdy2_eulerang`s) and which
//! `constraint` lets the shaft turn (`bearing1`, or `bearing3` at a constant speed). As
//! written, in the bodies' own frames; [`crate::model::turbine_htc`] reads the geometry.

use super::htc::{
    c2_def, count, damping, main_body, numbers, timoshenko_input, Block, C2Section, HtcDamping,
    Statement, TimoshenkoInput, Trail,
};
use super::text::parse_number;
use crate::error::Result;

/// A `concentrated_mass` of a body: at its node `node` (1-based) offset by `offset` (m, in the
/// body's frame), its mass (kg) and inertia tensor about its own centre in the body's frame
/// (kg·m²; HAWC2 gives `Ixx Iyy Izz` and optionally `Ixy Ixz Iyz`).
#[derive(Debug, Clone, PartialEq)]
pub struct ConcentratedMass {
    pub node: usize,
    pub offset: [f64; 3],
    pub mass: f64,
    pub inertia: [[f64; 3]; 3],
    pub file: String,
    pub line: usize,
}

/// A main body as the turbine reads it.
#[derive(Debug, Clone, PartialEq)]
pub struct TurbineBody {
    pub name: String,
    pub c2_def: Vec<C2Section>,
    /// None where the body has none (it is then not read as a beam).
    pub timoshenko: Option<TimoshenkoInput>,
    pub damping: Option<HtcDamping>,
    pub masses: Vec<ConcentratedMass>,
    pub file: String,
    pub line: usize,
}

/// A node of a body as an orientation or constraint names it: `last` or its number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeRef {
    Last,
    Number(usize),
}

/// `orientation › base`: the body fixed in space, where and how turned.
#[derive(Debug, Clone, PartialEq)]
pub struct Base {
    pub body: String,
    pub inipos: [f64; 3],
    /// Its `body_eulerang`s in order (deg about x, y, z).
    pub eulerang: Vec<[f64; 3]>,
    pub file: String,
    pub line: usize,
}

/// `orientation › relative`: body `child`'s node `child_node` on `parent`'s node
/// `parent_node`, its frame `parent`'s turned by the `mbdy2_eulerang`s in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Relative {
    pub parent: String,
    pub parent_node: NodeRef,
    pub child: String,
    pub child_node: NodeRef,
    pub eulerang: Vec<[f64; 3]>,
    pub file: String,
    pub line: usize,
}

/// A `constraint` between two bodies: its kind (`fix1`, `bearing1`, …), name, the bodies.
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    pub kind: String,
    pub name: String,
    pub parent: String,
    pub child: String,
    pub file: String,
    pub line: usize,
}

/// What the turbine reads from an htc model.
#[derive(Debug, Clone, PartialEq)]
pub struct HtcTurbine {
    pub file: String,
    pub base: Base,
    pub relatives: Vec<Relative>,
    pub constraints: Vec<Constraint>,
    /// Every body an orientation names, `copy_main_body` resolved.
    pub bodies: Vec<TurbineBody>,
}

impl HtcTurbine {
    pub fn body(&self, name: &str) -> Option<&TurbineBody> {
        self.bodies.iter().find(|b| b.name == name)
    }
}

/// The turbine of `model`. A missing block or statement is an error naming the file, the line
/// and the block; nothing is defaulted.
pub fn turbine(model: &Block) -> Result<HtcTurbine> {
    let top = Trail(Vec::new());
    let structure = model.block("new_htc_structure").ok_or_else(|| {
        top.error(
            &model.file,
            0,
            "expected a 'begin new_htc_structure;' block, found none",
        )
    })?;
    let trail = top.within(structure);
    let orientation = structure
        .block("orientation")
        .ok_or_else(|| trail.missing(structure, "a 'begin orientation;' block"))?;
    let o_trail = trail.within(orientation);
    let base_block = orientation
        .block("base")
        .ok_or_else(|| o_trail.missing(orientation, "a 'begin base;' block"))?;
    let b_trail = o_trail.within(base_block);
    let base = Base {
        body: word(base_block, "body", &b_trail)?,
        inipos: triple(
            required(base_block, "inipos", &b_trail)?,
            &b_trail,
            "inipos <x> <y> <z>;",
        )?,
        eulerang: base_block
            .statements("body_eulerang")
            .map(|s| triple(s, &b_trail, "body_eulerang <x> <y> <z>;"))
            .collect::<Result<_>>()?,
        file: base_block.file.clone(),
        line: base_block.line,
    };
    let relatives = orientation
        .blocks("relative")
        .map(|r| relative(r, &o_trail.within(r)))
        .collect::<Result<Vec<_>>>()?;
    let constraint = structure
        .block("constraint")
        .ok_or_else(|| trail.missing(structure, "a 'begin constraint;' block"))?;
    let c_trail = trail.within(constraint);
    let constraints = constraint
        .items
        .iter()
        .filter_map(|i| match i {
            super::htc::Item::Block(b) => Some(b),
            _ => None,
        })
        .filter(|b| b.statement("mbdy2").is_some())
        .map(|b| {
            let t = c_trail.within(b);
            Ok(Constraint {
                kind: b.name.clone(),
                name: b
                    .statement("name")
                    .and_then(|s| s.values.first().cloned())
                    .unwrap_or_default(),
                parent: body_of(b, "mbdy1", &t)?.0,
                child: body_of(b, "mbdy2", &t)?.0,
                file: b.file.clone(),
                line: b.line,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let mut names = vec![base.body.clone()];
    for r in &relatives {
        for n in [&r.parent, &r.child] {
            if !names.contains(n) {
                names.push(n.clone());
            }
        }
    }
    let bodies = names
        .iter()
        .map(|name| body(structure, name, &trail))
        .collect::<Result<Vec<_>>>()?;
    Ok(HtcTurbine {
        file: model.file.clone(),
        base,
        relatives,
        constraints,
        bodies,
    })
}

/// The main body `name` (its copy resolved), read as the turbine reads a body.
fn body(structure: &Block, name: &str, trail: &Trail) -> Result<TurbineBody> {
    let (block, _) = main_body(structure, name, trail)?;
    let trail = trail.within(block);
    let c2 = block
        .block("c2_def")
        .ok_or_else(|| trail.missing(block, "a 'begin c2_def;' block"))?;
    let c2_def = c2_def(c2, &trail.within(c2))?;
    let has_input =
        block.block("timoschenko_input").is_some() || block.block("timoshenko_input").is_some();
    let masses = block
        .statements("concentrated_mass")
        .map(|s| concentrated_mass(s, c2_def.len(), &trail))
        .collect::<Result<Vec<_>>>()?;
    Ok(TurbineBody {
        name: name.to_string(),
        timoshenko: if has_input {
            Some(timoshenko_input(block, &trail)?)
        } else {
            None
        },
        damping: damping(block, &trail)?,
        c2_def,
        masses,
        file: block.file.clone(),
        line: block.line,
    })
}

const MASS: &str =
    "concentrated_mass <node> <x> <y> <z> <m> <Ixx> <Iyy> <Izz> [<Ixy> <Ixz> <Iyz>];";

fn concentrated_mass(s: &Statement, nodes: usize, trail: &Trail) -> Result<ConcentratedMass> {
    let v = numbers(s, s.values.len(), trail, MASS)?;
    if v.len() != 8 && v.len() != 11 {
        return Err(trail.error(
            &s.file,
            s.line,
            format!("expected '{MASS}', found {} values", v.len()),
        ));
    }
    let node = count(v[0]).filter(|&n| n <= nodes).ok_or_else(|| {
        trail.error(
            &s.file,
            s.line,
            format!(
                "concentrated_mass: expected a node from 1 to {nodes}, found {}",
                v[0]
            ),
        )
    })?;
    if let Some(bad) = v[4..8].iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
        return Err(trail.error(
            &s.file,
            s.line,
            format!("concentrated_mass: expected a mass and moments of inertia ≥ 0, found {bad}"),
        ));
    }
    let (xy, xz, yz) = if v.len() == 11 {
        (v[8], v[9], v[10])
    } else {
        (0.0, 0.0, 0.0)
    };
    Ok(ConcentratedMass {
        node,
        offset: [v[1], v[2], v[3]],
        mass: v[4],
        inertia: [[v[5], xy, xz], [xy, v[6], yz], [xz, yz, v[7]]],
        file: s.file.clone(),
        line: s.line,
    })
}

fn relative(r: &Block, trail: &Trail) -> Result<Relative> {
    let (parent, parent_node) = body_of(r, "mbdy1", trail)?;
    let (child, child_node) = body_of(r, "mbdy2", trail)?;
    Ok(Relative {
        parent,
        parent_node,
        child,
        child_node,
        eulerang: r
            .statements("mbdy2_eulerang")
            .map(|s| triple(s, trail, "mbdy2_eulerang <x> <y> <z>;"))
            .collect::<Result<_>>()?,
        file: r.file.clone(),
        line: r.line,
    })
}

/// `mbdy1 <body> <node>;` (node `last` or a number; a constraint may give no node).
fn body_of(b: &Block, keyword: &str, trail: &Trail) -> Result<(String, NodeRef)> {
    let s = required(b, keyword, trail)?;
    let expected = format!("{keyword} <body> <node | last>;");
    match s.values.as_slice() {
        [name] => Ok((name.clone(), NodeRef::Last)),
        [name, node] => {
            let node = if node.eq_ignore_ascii_case("last") {
                NodeRef::Last
            } else {
                NodeRef::Number(parse_number(node).and_then(count).ok_or_else(|| {
                    trail.error(
                        &s.file,
                        s.line,
                        format!("expected '{expected}', found node '{node}'"),
                    )
                })?)
            };
            Ok((name.clone(), node))
        }
        _ => Err(trail.error(&s.file, s.line, format!("expected '{expected}'"))),
    }
}

fn required<'a>(b: &'a Block, keyword: &str, trail: &Trail) -> Result<&'a Statement> {
    b.statement(keyword)
        .ok_or_else(|| trail.missing(b, &format!("'{keyword} …;'")))
}

fn word(b: &Block, keyword: &str, trail: &Trail) -> Result<String> {
    let s = required(b, keyword, trail)?;
    s.values
        .first()
        .cloned()
        .ok_or_else(|| trail.error(&s.file, s.line, format!("expected '{keyword} <name>;'")))
}

fn triple(s: &Statement, trail: &Trail, expected: &str) -> Result<[f64; 3]> {
    let v = numbers(s, 3, trail, expected)?;
    Ok([v[0], v[1], v[2]])
}
