//! Newtype indices. Mixing up a corner with a vertex is the commonest bug
//! in corner-table code; separate types make it a compile error.

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        #[repr(transparent)]
        pub struct $name(pub u32);

        impl $name {
            /// The "no such element" sentinel.
            pub const NONE: $name = $name(u32::MAX);

            /// The index as `usize`, for slicing.
            #[inline(always)]
            pub fn idx(self) -> usize {
                self.0 as usize
            }

            /// True unless this is [`Self::NONE`].
            #[inline(always)]
            pub fn is_some(self) -> bool {
                self.0 != u32::MAX
            }

            /// True if this is [`Self::NONE`].
            #[inline(always)]
            pub fn is_none(self) -> bool {
                self.0 == u32::MAX
            }
        }

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                if self.is_none() {
                    write!(f, "none")
                } else {
                    write!(f, "{}", self.0)
                }
            }
        }
    };
}

id_type!(
    /// A corner: the `k`-th vertex slot (k = 0, 1, 2) of triangle `t` is corner `3t + k`.
    CornerId
);
id_type!(
    /// A vertex of a mesh.
    VertexId
);
id_type!(
    /// A triangle of a mesh.
    FaceId
);

impl CornerId {
    /// The triangle that owns this corner.
    #[inline(always)]
    pub fn face(self) -> FaceId {
        FaceId(self.0 / 3)
    }

    /// The next corner of the same triangle, counter-clockwise.
    #[inline(always)]
    pub fn next(self) -> CornerId {
        CornerId(if self.0 % 3 == 2 {
            self.0 - 2
        } else {
            self.0 + 1
        })
    }

    /// The previous corner of the same triangle (the next one twice).
    #[inline(always)]
    pub fn prev(self) -> CornerId {
        CornerId(if self.0 % 3 == 0 {
            self.0 + 2
        } else {
            self.0 - 1
        })
    }
}

impl FaceId {
    /// The first corner of this triangle; the others follow it.
    #[inline(always)]
    pub fn corner(self, k: u32) -> CornerId {
        CornerId(self.0 * 3 + k)
    }
}
