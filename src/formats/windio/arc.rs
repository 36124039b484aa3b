//! Placing the layers and webs on a section's contour: the `start_nd_arc`/`end_nd_arc` of every
//! layer, from the arc positions the file gives or, where it gives a width, from the width and
//! its anchor (a midpoint, one edge, or the pitch axis with an offset on one side), as the
//! ontology defines them.
//!
//! The contour is the section's airfoil scaled by the chord, in the chord frame: x along the
//! chord from the pitch axis toward the trailing edge, y toward the suction side, metres. Which
//! airfoil shape a station has (the ontology interpolates it in relative thickness) is the
//! section analysis' choice; this module takes the contour it made.
//!
//! Rules, from the ontology's definitions:
//! - the non-dimensional arc s is the arc length from the trailing edge on the suction side,
//!   over the perimeter; for an open (flatback) trailing edge s = 0 and s = 1 are at its middle;
//! - the leading edge is the contour point of least x (midway along the arc between the first
//!   and last such point, for a blunt nose);
//! - a width w (m) centred on s_m spans s_m ∓ w/(2L) (L the perimeter); from a start s_0 it
//!   spans s_0 to s_0 + w/L, up to an end s_1 from s_1 − w/L;
//! - an edge locked to `LE` is at the leading edge, to `TE` at s = 0 (a start or midpoint) or
//!   s = 1 (an end), whatever values accompany it; an edge locked to another layer takes the
//!   values given with it, or else that layer's adjacent edge (a start the other's end, an end
//!   the other's start);
//! - about the pitch axis: the axis through the pitch axis turned by the rotation r from the
//!   chord (r = −twist for `fixed: twist`), the offset point at distance d along it, and the
//!   layer's middle (or the web's edges) where the line through that point perpendicular to
//!   the axis crosses the contour on the layer's side (a web: its start on the suction side,
//!   its end on the pressure side);
//! - a layer running over the trailing edge has start > end (e.g. 0.97 to 0.03).

use super::blade::{Anchor, ArcPosition, Fixed, Layer, Placement, Rotation, Side, Web};
use super::distribution::Distribution;
use crate::error::{Error, Result};

impl Distribution {
    /// The value at `at` by straight lines between the grid points, held at the end values
    /// beyond the grid.
    pub fn linear(&self, at: f64) -> f64 {
        let (g, v) = (&self.grid, &self.values);
        let n = g.len();
        if at <= g[0] {
            return v[0];
        }
        if at >= g[n - 1] {
            return v[n - 1];
        }
        let i = g.partition_point(|&x| x <= at).clamp(1, n - 1);
        let t = (at - g[i - 1]) / (g[i] - g[i - 1]);
        v[i - 1] + t * (v[i] - v[i - 1])
    }
}

/// A section's outer contour for placing arc positions.
#[derive(Debug, Clone, PartialEq)]
pub struct Contour {
    /// From s = 0 to s = 1, metres, chord frame.
    points: Vec<[f64; 2]>,
    /// Cumulative arc length at each point, metres.
    arc: Vec<f64>,
    /// Non-dimensional arc of the leading edge.
    leading_edge: f64,
}

impl Contour {
    /// The contour of an airfoil listed in chord units as WindIO lists it (from the trailing
    /// edge over the suction side round the leading edge and back), scaled by `chord` (m) and
    /// shifted so that the pitch axis, at `pitch_axis` of the chord from the leading edge, is
    /// the origin.
    pub fn new(x: &[f64], y: &[f64], chord: f64, pitch_axis: f64) -> Result<Contour> {
        let fail = |m: String| Error::Invalid {
            origin: "section contour".into(),
            message: m,
        };
        if x.len() != y.len() || x.len() < 3 {
            return Err(fail(format!(
                "expected at least three points with as many x as y, found {} x and {} y",
                x.len(),
                y.len()
            )));
        }
        if !(chord.is_finite() && chord > 0.0 && pitch_axis.is_finite()) {
            return Err(fail(format!(
                "expected a chord > 0 and a finite pitch axis, found {chord} and {pitch_axis}"
            )));
        }
        let place = |i: usize| [(x[i] - pitch_axis) * chord, y[i] * chord];
        let mut points: Vec<[f64; 2]> = (0..x.len()).map(place).collect();
        let (first, last) = (points[0], points[points.len() - 1]);
        if first != last {
            let mid = [(first[0] + last[0]) / 2.0, (first[1] + last[1]) / 2.0];
            points.insert(0, mid);
            points.push(mid);
        }
        let mut arc = Vec::with_capacity(points.len());
        let mut total = 0.0;
        arc.push(0.0);
        for w in points.windows(2) {
            total += (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            arc.push(total);
        }
        if !(total.is_finite() && total > 0.0) {
            return Err(fail(format!(
                "expected a contour of positive finite length, found {total}"
            )));
        }
        // The ontology lists the suction side first: from the trailing edge the contour turns
        // counter-clockwise in (x toward the trailing edge, y toward the suction side). Listed
        // the other way, every arc position would land on the opposite side.
        let twice_area: f64 = points
            .windows(2)
            .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
            .sum();
        if twice_area <= 0.0 {
            return Err(fail(
                "expected the contour from the trailing edge over the suction side (y > 0) first, \
                 found it listed the other way round"
                    .into(),
            ));
        }
        // Several points may share the least x (a blunt nose); the edge is midway between them.
        let least = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        let foremost: Vec<usize> = (0..points.len())
            .filter(|&i| points[i][0] == least)
            .collect();
        let (first, last) = (foremost[0], foremost[foremost.len() - 1]);
        let leading_edge = (arc[first] + arc[last]) / 2.0 / total;
        Ok(Contour {
            points,
            arc,
            leading_edge,
        })
    }

    /// The contour's points from s = 0 to s = 1 (a closed loop: the last is the first), m,
    /// chord frame.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Perimeter, m.
    pub fn length(&self) -> f64 {
        self.arc[self.arc.len() - 1]
    }

    /// Non-dimensional arc of the leading edge.
    pub fn leading_edge(&self) -> f64 {
        self.leading_edge
    }

    /// Where the line across the chord at `x` (m, chord frame) meets the suction side and the
    /// pressure side (non-dimensional arcs), if it meets both.
    pub fn across_chord(&self, x: f64) -> Option<(f64, f64)> {
        let le = self.leading_edge;
        let suction = self.crossing([x, 0.0], [1.0, 0.0], 0.0, le)?;
        let pressure = self.crossing([x, 0.0], [1.0, 0.0], le, 1.0)?;
        Some((suction, pressure))
    }

    /// The non-dimensional arc where the line through `point` perpendicular to `axis` (a unit
    /// vector) first crosses the contour between s = `from` and s = `to`.
    fn crossing(&self, point: [f64; 2], axis: [f64; 2], from: f64, to: f64) -> Option<f64> {
        let total = self.length();
        let f = |p: [f64; 2]| (p[0] - point[0]) * axis[0] + (p[1] - point[1]) * axis[1];
        for i in 0..self.points.len() - 1 {
            let (s0, s1) = (self.arc[i] / total, self.arc[i + 1] / total);
            if s1 < from || s0 > to {
                continue;
            }
            let (f0, f1) = (f(self.points[i]), f(self.points[i + 1]));
            if f0 == 0.0 {
                return Some(s0);
            }
            if f0 * f1 < 0.0 {
                let t = f0 / (f0 - f1);
                return Some(s0 + t * (s1 - s0));
            }
        }
        None
    }
}

/// What one span station gives the placement: where it is along the span (`eta`), the twist
/// there (rad) and the contour.
pub struct Station<'c> {
    pub eta: f64,
    pub twist: f64,
    pub contour: &'c Contour,
}

/// Brings an arc value back into [0, 1] across the trailing edge.
fn wrap(s: f64) -> f64 {
    if s < 0.0 {
        s + 1.0
    } else if s > 1.0 {
        s - 1.0
    } else {
        s
    }
}

/// Which edge of a layer an arc position is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Edge {
    Start,
    End,
    Middle,
}

struct Placer<'a, 'c> {
    layers: &'a [Layer],
    at: &'a Station<'c>,
    file: &'a str,
    done: Vec<Option<(f64, f64)>>,
    busy: Vec<bool>,
}

impl Placer<'_, '_> {
    fn fail(&self, layer: &Layer, message: String) -> Error {
        Error::format(
            self.file,
            layer.line,
            format!("layer `{}` at span {}: {message}", layer.name, self.at.eta),
        )
    }

    fn position(&mut self, i: usize, p: &ArcPosition, edge: Edge) -> Result<f64> {
        match (&p.fixed, &p.values) {
            (Some(Fixed::LeadingEdge), _) => Ok(self.at.contour.leading_edge()),
            (Some(Fixed::TrailingEdge), _) => Ok(if edge == Edge::End { 1.0 } else { 0.0 }),
            (_, Some(v)) => Ok(v.linear(self.at.eta)),
            (Some(Fixed::Layer(other)), None) => {
                let j = self
                    .layers
                    .iter()
                    .position(|l| &l.name == other)
                    .ok_or_else(|| {
                        self.fail(&self.layers[i], format!("no layer named `{other}`"))
                    })?;
                let (start, end) = self.place(j)?.ok_or_else(|| {
                    self.fail(
                        &self.layers[i],
                        format!("`{other}` is on a web, not on the shell; an edge cannot be locked to it"),
                    )
                })?;
                Ok(match edge {
                    Edge::Start => end,
                    Edge::End => start,
                    Edge::Middle => wrap((start + end) / 2.0),
                })
            }
            (None, None) => Err(self.fail(
                &self.layers[i],
                "an arc position with neither values nor fixed".into(),
            )),
        }
    }

    fn pitch_axis_crossing(
        &self,
        layer: &Layer,
        side: Side,
        offset: &Distribution,
        rotation: Option<&Rotation>,
    ) -> Result<f64> {
        let r = rotation_at(rotation, self.at).ok_or_else(|| {
            self.fail(
                layer,
                "a width about the pitch axis needs a rotation (values or fixed: twist)".into(),
            )
        })?;
        let axis = [r.cos(), r.sin()];
        let d = offset.linear(self.at.eta);
        let point = [d * axis[0], d * axis[1]];
        let le = self.at.contour.leading_edge();
        let (from, to) = match side {
            Side::Suction => (0.0, le),
            Side::Pressure => (le, 1.0),
        };
        self.at.contour.crossing(point, axis, from, to).ok_or_else(|| {
            self.fail(
                layer,
                format!("the line at offset {d} m from the pitch axis does not meet the {side:?} side"),
            )
        })
    }

    fn place(&mut self, i: usize) -> Result<Option<(f64, f64)>> {
        if let Some(done) = self.done[i] {
            return Ok(Some(done));
        }
        let layers = self.layers;
        let layer = &layers[i];
        if self.busy[i] {
            return Err(self.fail(
                layer,
                "its edges are locked to layers locked back to it".into(),
            ));
        }
        self.busy[i] = true;
        let half_width = |w: &Distribution| w.linear(self.at.eta) / 2.0 / self.at.contour.length();
        let placed = match layer.placement() {
            None => return Err(self.fail(layer, "nothing places it".into())),
            Some(Placement::Web(_)) => None,
            Some(Placement::WholeSection) => Some((0.0, 1.0)),
            Some(Placement::Arcs { start, end }) => Some((
                self.position(i, start, Edge::Start)?,
                self.position(i, end, Edge::End)?,
            )),
            Some(Placement::Width { width, anchor }) => {
                let h = half_width(width);
                Some(match anchor {
                    Anchor::Midpoint(m) => {
                        let mid = self.position(i, m, Edge::Middle)?;
                        (wrap(mid - h), wrap(mid + h))
                    }
                    Anchor::Start(s) => {
                        let s0 = self.position(i, s, Edge::Start)?;
                        (s0, wrap(s0 + 2.0 * h))
                    }
                    Anchor::End(e) => {
                        let s1 = self.position(i, e, Edge::End)?;
                        (wrap(s1 - 2.0 * h), s1)
                    }
                    Anchor::PitchAxis {
                        side,
                        offset,
                        rotation,
                    } => {
                        let mid = self.pitch_axis_crossing(layer, side, offset, rotation)?;
                        (wrap(mid - h), wrap(mid + h))
                    }
                })
            }
        };
        self.busy[i] = false;
        self.done[i] = placed;
        Ok(placed)
    }
}

fn rotation_at(rotation: Option<&Rotation>, at: &Station) -> Option<f64> {
    let r = rotation?;
    match &r.values {
        Some(v) => Some(v.linear(at.eta)),
        None if r.fixed_to_twist => Some(-at.twist),
        None => None,
    }
}

/// The (start, end) non-dimensional arc of every layer at a station, in the layers' order;
/// `None` for a layer on a web. `file` is the name errors give.
pub fn place_layers(layers: &[Layer], at: &Station, file: &str) -> Result<Vec<Option<(f64, f64)>>> {
    let mut placer = Placer {
        layers,
        at,
        file,
        done: vec![None; layers.len()],
        busy: vec![false; layers.len()],
    };
    (0..layers.len()).map(|i| placer.place(i)).collect()
}

/// Where a web meets the shell at a station: (start on the suction side, end on the pressure
/// side), non-dimensional arc.
pub fn place_web(web: &Web, at: &Station, file: &str) -> Result<(f64, f64)> {
    let fail = |m: String| {
        Error::format(
            file,
            web.line,
            format!("web `{}` at span {}: {m}", web.name, at.eta),
        )
    };
    let given = |p: &Option<ArcPosition>, edge_at_te: f64| -> Option<f64> {
        let p = p.as_ref()?;
        match (&p.fixed, &p.values) {
            (Some(Fixed::LeadingEdge), _) => Some(at.contour.leading_edge()),
            (Some(Fixed::TrailingEdge), _) => Some(edge_at_te),
            (_, Some(v)) => Some(v.linear(at.eta)),
            _ => None,
        }
    };
    if let (Some(s), Some(e)) = (given(&web.start_nd_arc, 0.0), given(&web.end_nd_arc, 1.0)) {
        return Ok((s, e));
    }
    let offset = web
        .offset
        .as_ref()
        .ok_or_else(|| fail("neither arc positions nor an offset place it".into()))?;
    let r = rotation_at(web.rotation.as_ref(), at)
        .ok_or_else(|| fail("an offset needs a rotation (values or fixed: twist)".into()))?;
    let axis = [r.cos(), r.sin()];
    let d = offset.linear(at.eta);
    let point = [d * axis[0], d * axis[1]];
    let le = at.contour.leading_edge();
    let start = at
        .contour
        .crossing(point, axis, 0.0, le)
        .ok_or_else(|| fail(format!("its plane at {d} m does not meet the suction side")))?;
    let end = at.contour.crossing(point, axis, le, 1.0).ok_or_else(|| {
        fail(format!(
            "its plane at {d} m does not meet the pressure side"
        ))
    })?;
    Ok((start, end))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::windio::parse;
    use std::f64::consts::PI;

    /// A circle of unit radius about the pitch axis: chord 2 m, pitch axis at mid-chord, listed
    /// from the trailing edge over the suction side.
    fn circle() -> Contour {
        let n = 2000;
        let (x, y): (Vec<f64>, Vec<f64>) = (0..=n)
            .map(|i| {
                let t = 2.0 * PI * i as f64 / n as f64;
                (0.5 + 0.5 * t.cos(), 0.5 * t.sin())
            })
            .unzip();
        Contour::new(&x, &y, 2.0, 0.5).unwrap()
    }

    fn read_test_file() -> crate::formats::windio::WindIo {
        parse(crate::formats::windio::tests::GOOD, "t.yaml").unwrap()
    }

    #[test]
    fn a_circle_places_each_definition_where_geometry_puts_it() {
        let contour = circle();
        assert!((contour.length() - 2.0 * PI).abs() < 1e-5);
        assert!((contour.leading_edge() - 0.5).abs() < 1e-12);
        let w = read_test_file();
        let twist = 0.1;
        let at = Station {
            eta: 0.0,
            twist,
            contour: &contour,
        };
        let placed = place_layers(&w.blade.structure.layers, &at, "t.yaml").unwrap();
        let l = contour.length();
        assert_eq!(placed[0], Some((0.0, 1.0)));
        // The cap: 0.5 m wide, centred where the line through the pitch axis perpendicular to
        // the root frame's y axis (turned −twist from the chord) meets the suction side.
        let mid = (PI / 2.0 - twist) / (2.0 * PI);
        let (s, e) = placed[1].unwrap();
        assert!((s - (mid - 0.25 / l)).abs() < 1e-5, "{s}");
        assert!((e - (mid + 0.25 / l)).abs() < 1e-5, "{e}");
        // The nose: 0.4 m about the leading edge.
        let (ns, ne) = placed[2].unwrap();
        assert!((ns - (0.5 - 0.2 / l)).abs() < 1e-5 && (ne - (0.5 + 0.2 / l)).abs() < 1e-5);
        // The filler runs from the cap's end to the nose's start.
        assert_eq!(placed[3], Some((e, ns)));
        assert_eq!(placed[4], None);
        // The web's plane: through the pitch axis, ends on both sides.
        let (ws, we) = place_web(&w.blade.structure.webs[0], &at, "t.yaml").unwrap();
        assert!((ws - mid).abs() < 1e-5, "{ws}");
        assert!((we - (1.5 * PI - twist) / (2.0 * PI)).abs() < 1e-5, "{we}");
    }

    #[test]
    fn edges_locked_in_a_loop_are_refused_not_followed_forever() {
        let mut w = read_test_file();
        let layers = &mut w.blade.structure.layers;
        let lock = |name: &str| ArcPosition {
            fixed: Some(Fixed::Layer(name.into())),
            values: None,
            line: 1,
        };
        layers[1].width = None;
        layers[1].start_nd_arc = Some(lock("filler"));
        layers[1].end_nd_arc = Some(lock("filler"));
        let contour = circle();
        let at = Station {
            eta: 0.5,
            twist: 0.0,
            contour: &contour,
        };
        let e = place_layers(layers, &at, "t.yaml").unwrap_err().to_string();
        assert!(e.contains("locked to layers locked back to it"), "{e}");
        layers[1].start_nd_arc = Some(lock("web_skin"));
        let e = place_layers(layers, &at, "t.yaml").unwrap_err().to_string();
        assert!(e.contains("`web_skin` is on a web"), "{e}");
    }

    #[test]
    fn an_offset_beyond_the_section_is_named() {
        let mut w = read_test_file();
        let cap = &mut w.blade.structure.layers[1];
        cap.offset.as_mut().unwrap().values = vec![3.0, 3.0];
        let contour = circle();
        let at = Station {
            eta: 0.5,
            twist: 0.0,
            contour: &contour,
        };
        let e = place_layers(&w.blade.structure.layers, &at, "t.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t.yaml:"), "{e}");
        assert!(
            e.contains("layer `cap` at span 0.5: the line at offset 3 m"),
            "{e}"
        );
    }

    #[test]
    fn an_open_trailing_edge_starts_the_arc_at_its_middle() {
        // A 1 m × 0.2 m rectangle open at the trailing edge (x = 1): the arc runs from the
        // middle of the gap, so the perimeter includes the gap and the leading edge is halfway.
        let x = [1.0, 0.0, 0.0, 1.0];
        let y = [0.1, 0.1, -0.1, -0.1];
        let c = Contour::new(&x, &y, 1.0, 0.0).unwrap();
        assert!((c.length() - 2.4).abs() < 1e-12);
        assert!((c.leading_edge() - 0.5).abs() < 1e-12);
        let e = Contour::new(&[1.0, 0.0, 0.0, 1.0], &[-0.1, -0.1, 0.1, 0.1], 1.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("suction side (y > 0) first"), "{e}");
    }

    #[test]
    fn a_width_from_the_trailing_edge_runs_toward_the_leading_edge() {
        let mut w = read_test_file();
        let nose = &mut w.blade.structure.layers[2];
        nose.midpoint_nd_arc = None;
        nose.end_nd_arc = Some(ArcPosition {
            fixed: Some(Fixed::TrailingEdge),
            values: None,
            line: 1,
        });
        let contour = circle();
        let at = Station {
            eta: 0.5,
            twist: 0.0,
            contour: &contour,
        };
        let placed = place_layers(&w.blade.structure.layers, &at, "t.yaml").unwrap();
        let (s, e) = placed[2].unwrap();
        assert_eq!(e, 1.0);
        assert!((s - (1.0 - 0.4 / contour.length())).abs() < 1e-12, "{s}");
    }

    #[test]
    fn linear_values_hold_beyond_the_grid() {
        let d = Distribution {
            grid: vec![0.2, 0.6],
            values: vec![1.0, 3.0],
            line: 1,
        };
        assert_eq!(d.linear(0.0), 1.0);
        assert_eq!(d.linear(0.4), 2.0);
        assert_eq!(d.linear(1.0), 3.0);
    }
}
