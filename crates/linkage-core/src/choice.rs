//! The string choices users write (`"open"`/`"crossed"`, `"left"`/`"right"`, …), defined once
//! per enum: [`choice_names!`] gives a two-valued enum its `NAMES`, `name`, `FromStr` (with
//! [`crate::Error::InvalidChoice`] naming both) and `Display`, all from one list of names.

/// `choice_names!(Enum, "what", VariantA => "a", VariantB => "b")`: the names of a two-valued
/// enum, its parsing and its display (see the module).
macro_rules! choice_names {
    ($ty:ident, $what:literal, $a:ident => $na:literal, $b:ident => $nb:literal) => {
        impl $ty {
            /// Every name [`FromStr`](core::str::FromStr) takes, in declaration order.
            pub const NAMES: [&'static str; 2] = [$na, $nb];

            /// The name users write (one of [`Self::NAMES`]).
            pub fn name(self) -> &'static str {
                match self {
                    $ty::$a => $na,
                    $ty::$b => $nb,
                }
            }
        }

        impl core::str::FromStr for $ty {
            type Err = crate::error::Error;

            /// The value named by one of [`Self::NAMES`], exactly.
            ///
            /// # Errors
            /// [`Error::InvalidChoice`](crate::Error::InvalidChoice) for any other name.
            fn from_str(name: &str) -> Result<Self, crate::error::Error> {
                match name {
                    $na => Ok($ty::$a),
                    $nb => Ok($ty::$b),
                    _ => Err(crate::error::Error::InvalidChoice {
                        what: $what,
                        choices: concat!("'", $na, "' or '", $nb, "'"),
                    }),
                }
            }
        }

        impl core::fmt::Display for $ty {
            /// The name (see [`Self::NAMES`]).
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

pub(crate) use choice_names;
