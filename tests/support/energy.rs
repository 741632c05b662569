//! The energy checks a solved bounce must pass, shared by the frame's tests.

use snapback::model::{Energy, Params, solve};

/// The budget balances to 1e-9 of the incoming energy, no loss is negative (to 1e-12 of it), and the ball,
/// the strings, the ball's spring and the frame leave with no more than came in.
pub fn assert_nothing_created(e: &Energy, what: &str) {
    assert!(e.residual.abs() < 1e-9, "residual: {e:?} {what}");
    let losses = [
        e.friction_loss,
        e.normal_loss,
        e.cart_friction_loss,
        e.dashpot_loss,
    ];
    for loss in losses {
        assert!(loss >= -1e-12 * e.initial, "a negative loss: {e:?} {what}");
    }
    let kept = e.final_ball + e.final_cart + e.ball_spring + e.frame;
    assert!(
        kept <= e.initial * (1.0 + 1e-12),
        "energy created: {e:?} {what}"
    );
}

/// Solves each bounce and checks that none creates energy ([`assert_nothing_created`]) and that at least
/// `floor` of them lost more than a millionth of their energy to the string friction.
pub fn assert_string_friction_works(bounces: impl IntoIterator<Item = Params>, floor: usize) {
    let mut worked = 0;
    for (case, p) in bounces.into_iter().enumerate() {
        let b = solve(&p).unwrap_or_else(|e| panic!("case {case}: {e}\n{p:?}"));
        let e = b.energy();
        assert_nothing_created(&e, &format!("case {case}: {p:?}"));
        worked += usize::from(e.cart_friction_loss > 1e-6 * e.initial);
    }
    assert!(
        worked >= floor,
        "only {worked} bounces lost energy to string friction"
    );
}
