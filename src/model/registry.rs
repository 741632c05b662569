//! The contact models, listed once: which model a [`Params`] is ([`Params::model`]), the words the views
//! use for it, and the closed form of one phase of each ([`Motion`]). Adding a model adds a line here;
//! nothing else in the core branches on the model.

use super::cart::CartMotion;
use super::chain::ChainMotion;
use super::compliant::CompliantMotion;
use super::contact::PhaseMotion;
use super::frame::FrameMotion;
use super::params::Params;

/// The ball: rigid (the paper's) or tangentially compliant (a spring and dashpot to its contact patch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BallKind {
    Rigid,
    Compliant,
}

/// What the ball touches: the paper's single cart, or a chain of masses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SupportKind {
    Cart,
    Chain,
}

/// What the support's spring (a chain's last spring) is tied to: the paper's wall, or a frame free
/// along the surface (issue 23).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    Clamped,
    Free,
}

/// The contact model of one set of parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelKind {
    pub ball: BallKind,
    pub support: SupportKind,
    pub frame: FrameKind,
}

/// The words a view uses for the surface of a model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Words {
    /// What the ball touches: `cart`, `first mass`.
    pub touched: &'static str,
    /// The surface with its springs, as the energy budget names it: `cart + spring`, `chain + springs`.
    pub surface_springs: &'static str,
    /// The energy left in the surface: `left in the cart`, `left in the chain`.
    pub left_in: &'static str,
    /// The string friction's loss: `lost at the cart`, `lost at mass 1`.
    pub lost_at: &'static str,
}

impl FrameKind {
    /// What the support is tied to, as a view names it: `wall`, `frame`.
    pub fn word(self) -> &'static str {
        match self {
            FrameKind::Clamped => "wall",
            FrameKind::Free => "frame",
        }
    }
}

impl SupportKind {
    pub fn words(self) -> &'static Words {
        match self {
            SupportKind::Cart => &Words {
                touched: "cart",
                surface_springs: "cart + spring",
                left_in: "left in the cart",
                lost_at: "lost at the cart",
            },
            SupportKind::Chain => &Words {
                touched: "first mass",
                surface_springs: "chain + springs",
                left_in: "left in the chain",
                lost_at: "lost at mass 1",
            },
        }
    }
}

impl ModelKind {
    /// The words for this model's surface.
    pub fn words(self) -> &'static Words {
        self.support.words()
    }

    /// True for a ball with a contact patch (a spring and dashpot between the ball and the surface).
    pub fn compliant(self) -> bool {
        self.ball == BallKind::Compliant
    }
}

impl Params {
    /// The contact model these parameters describe: a compliant ball when `ball_stiffness` > 0, on a
    /// chain when `chain` > 1, tied to a free frame when `frame_mass` > 0. The one place that decides; the solver, the limits and the views ask it.
    pub fn model(&self) -> ModelKind {
        ModelKind {
            ball: if self.ball_stiffness > 0.0 {
                BallKind::Compliant
            } else {
                BallKind::Rigid
            },
            support: if self.chain > 1.0 {
                SupportKind::Chain
            } else {
                SupportKind::Cart
            },
            frame: if self.frame_mass > 0.0 {
                FrameKind::Free
            } else {
                FrameKind::Clamped
            },
        }
    }

    /// What the ball touches, as the outputs name it: the cart, or a chain's first mass.
    pub fn touched(&self) -> &'static str {
        self.model().words().touched
    }
}

/// One phase's closed form, of whichever model solved it.
#[derive(Clone, Debug)]
pub enum Motion {
    /// The rigid ball on the single cart (sliding or gripping).
    Cart(CartMotion),
    /// The rigid ball on a chain of masses (sliding or gripping).
    Chain(ChainMotion),
    /// A compliant ball, on the single cart or on a chain (unboxed: a slide is no larger than the
    /// framed cart's phase, and a grip's large closed form is boxed inside it).
    Compliant(CompliantMotion),
    /// The rigid ball on the single cart tied to a free frame.
    Frame(FrameMotion),
}

impl Motion {
    /// The model's own answers about its phase.
    #[inline]
    pub fn get(&self) -> &dyn PhaseMotion {
        match self {
            Motion::Cart(m) => m,
            Motion::Chain(m) => m.as_ref(),
            Motion::Compliant(m) => m,
            Motion::Frame(m) => m,
        }
    }
}

impl From<CartMotion> for Motion {
    fn from(motion: CartMotion) -> Self {
        Motion::Cart(motion)
    }
}

impl From<ChainMotion> for Motion {
    fn from(motion: ChainMotion) -> Self {
        Motion::Chain(motion)
    }
}

impl From<CompliantMotion> for Motion {
    fn from(motion: CompliantMotion) -> Self {
        Motion::Compliant(motion)
    }
}

impl From<FrameMotion> for Motion {
    fn from(motion: FrameMotion) -> Self {
        Motion::Frame(motion)
    }
}
