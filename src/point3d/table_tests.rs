use super::describing::unit_cell;
use super::table::{
    compute, grid_node, parse, to_csv, unit_cell_tabulated, Block, A_MAX, B_MIN, NV, NZ,
    TABLE_TOLERANCE,
};

const CSV: &str = include_str!("unit_cell_table.csv");

/// Writes `unit_cell_table.csv` from the integrated unit cell (about two minutes on two
/// cores); the test below checks the committed table against the integration.
#[test]
#[ignore = "regenerates src/point3d/unit_cell_table.csv: cargo test --release --lib regenerate_unit_cell_table -- --ignored"]
fn regenerate_unit_cell_table() {
    let t = compute(2);
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/src/point3d/unit_cell_table.csv"
    );
    std::fs::write(path, to_csv(&t)).unwrap();
}

/// The committed table holds the integrated cell at its nodes (a sample of nodes below
/// a = 10³, where a node takes milliseconds), written without loss.
#[test]
fn the_committed_table_is_the_integrated_unit_cell_at_its_nodes() {
    let t = parse(CSV).expect("complete table");
    let mut checked = 0;
    for block in [Block::Lower, Block::Upper] {
        for i in (0..NZ).step_by(7) {
            for j in (0..NV).step_by(9) {
                let (a, b) = grid_node(block, i, j);
                if a > 1e3 {
                    continue;
                }
                let h = unit_cell(a, b);
                let node = t.grid[block as usize][i * NV + j];
                assert_eq!(node, [h.c1, h.s1, h.c2, h.s2], "{block:?} node ({i}, {j})");
                checked += 1;
            }
        }
    }
    assert!(checked >= 20, "{checked}");
}

/// A corrupt or truncated table is refused, not read as zeros.
#[test]
fn a_corrupt_table_is_refused() {
    assert!(parse(&CSV[..CSV.len() / 2]).is_none());
    assert!(parse(&CSV.replacen("lower,0,0,", "lower,0,0,x", 1)).is_none());
    assert!(parse(&CSV.replacen("upper,1,1,", "upper,999,1,", 1)).is_none());
}

/// Off the nodes, over the whole plane (a from 0.5 to 3·A_MAX, b/a from 1e-6 to 1 and the
/// roles swapped), the interpolated harmonics are within TABLE_TOLERANCE of the cell's
/// limit force of the integrated ones, and the energy within the same share of the
/// path's perimeter.
#[test]
fn tabulated_unit_cell_matches_the_integrated_one() {
    // A fixed low-discrepancy sample (golden-ratio sequence) of ln a and ln(b/a).
    let (g1, g2) = (0.618_033_988_749_894_9, 0.754_877_666_246_692_7);
    let mut worst: f64 = 0.0;
    let mut worst_at = (0.0, 0.0);
    // Near-circles just above the onset switch between sliding all round and sticking at
    // the minor axis's ends: the table's hardest corner, sampled on purpose.
    let corner = [
        (1.06, 0.95),
        (1.06, 0.975),
        (1.44, 0.9),
        (2.66, 0.9),
        (90.0, 4.3),
    ];
    let sample = (1..=120).filter_map(|n| {
        let (x, y) = ((n as f64 * g1).fract(), (n as f64 * g2).fract());
        let a = (0.5f64.ln() + x * (3.0 * A_MAX / 0.5).ln()).exp();
        // Beyond a = 3e3 the integration is slow (steps ∝ a): a sparser sample there.
        if a > 3e3 && n % 6 != 0 {
            return None;
        }
        let e = (y * 1e-6f64.ln()).exp();
        Some(if n % 3 == 0 { (a * e, a) } else { (a, a * e) })
    });
    for (a, b) in corner.into_iter().chain(sample) {
        let exact = unit_cell(a, b);
        let table = unit_cell_tabulated(a, b);
        let err = [
            exact.c1 - table.c1,
            exact.s1 - table.s1,
            exact.c2 - table.c2,
            exact.s2 - table.s2,
        ]
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
        let perimeter = 4.0 * a.max(b) + 2.0 * a.min(b);
        let energy_err = (exact.energy - table.energy).abs() / (std::f64::consts::PI * perimeter);
        if err.max(energy_err) > worst {
            worst = err.max(energy_err);
            worst_at = (a, b);
        }
    }
    println!("tabulated unit cell: worst error {worst:.2e} f at (a, b) = {worst_at:?} x");
    assert!(worst <= TABLE_TOLERANCE, "{worst:e} at {worst_at:?}");
    // Below B_MIN and at the stick boundary the table is continuous.
    let (lo, hi) = (
        unit_cell_tabulated(5.0, 0.999 * B_MIN),
        unit_cell_tabulated(5.0, 1.001 * B_MIN),
    );
    assert!((lo.c1 - hi.c1).abs() < 1e-6 && (lo.s2 - hi.s2).abs() < 1e-5);
    let stick = unit_cell_tabulated(1.0, 0.5);
    assert_eq!((stick.c1, stick.s2, stick.energy), (1.0, 0.5, 0.0));
}
