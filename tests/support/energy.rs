//! The energy checks a solved bounce must pass, shared by the frame's tests.

use snapback::model::Energy;

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
