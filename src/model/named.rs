//! `named!`: an enum whose variants each have one name, as the spec writes it (the effects, the
//! contact laws, the geometry modes, the deviation kinds, ...).

/// An enum whose variants each have one name, as the spec writes it: `ALL`, `name`,
/// `from_name`, `names` (for messages), `Display` and `FromStr`, from one table.
macro_rules! named {
    ($ty:ident $what:literal { $($variant:ident => $name:literal),+ $(,)? }) => {
        impl $ty {
            /// Every variant, in the order of the table (the order of `names`).
            pub const ALL: [$ty; [$($name),+].len()] = [$($ty::$variant),+];

            /// The name the spec and the outputs use.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }

            /// The variant the spec names `name`, if any (the inverse of `name`).
            pub fn from_name(name: &str) -> Option<$ty> {
                Self::ALL.into_iter().find(|v| v.name() == name)
            }

            /// Every name, comma-separated, for messages.
            pub fn names() -> String {
                Self::ALL.map(|v| v.name()).join(", ")
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = String;

            fn from_str(s: &str) -> Result<Self, String> {
                Self::from_name(s)
                    .ok_or_else(|| format!("unknown {} `{s}`; known: {}", $what, Self::names()))
            }
        }
    };
}
