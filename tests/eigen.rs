use flutterscope::analysis::eigen::*;
use flutterscope::preset::Preset;
use nalgebra::Complex;

#[test]
fn debug_shares() {
    let p = Preset::load("liu2017", &[]).unwrap();
    let ls = linear_system(&p).unwrap();
    let nat = ls.structure.natural_modes().unwrap();
    for m in &nat { println!("{} {:.3} Hz ts {:.3}", m.label, m.frequency_hz, m.torsion_share); }
    let s = analyse_system(&ls).unwrap();
    for r in &s.eigenvalues {
        let e: Vec<f64> = nat.iter().map(|m| {
            let mphi = &ls.structure.mass * &m.shape;
            let mm = m.shape.dot(&mphi);
            let eta: Complex<f64> = mphi.iter().zip(&r.shape).map(|(w, q)| q * *w).sum();
            eta.norm_sqr() / mm
        }).collect();
        let t: f64 = e.iter().sum();
        println!("{:16} {:10.3} {:10.3} ts {:.3} | {}", r.label, r.re, r.im, ls.structure.torsion_share(&r.shape),
            e.iter().map(|x| format!("{:.2}", x / t)).collect::<Vec<_>>().join(" "));
    }
}
