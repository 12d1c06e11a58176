//! Options chosen by name on the command line and named in reports (the
//! ray-triangle test, the torus method): an enum whose values each have a
//! name, written once with [`named_option!`].

/// An enum chosen by name.
pub trait NamedOption: Copy + 'static {
    /// Every value, in the order help and errors list them.
    fn all() -> &'static [Self];

    /// Its name on the command line and in reports.
    fn name(self) -> &'static str;

    /// The value named `name`; the error lists the names, for clap to show
    /// after "invalid value".
    fn from_name(name: &str) -> Result<Self, String> {
        let all = Self::all().iter().copied();
        all.clone().find(|o| o.name() == name).ok_or_else(|| {
            let names: Vec<&str> = all.map(Self::name).collect();
            format!("one of {}", names.join(", "))
        })
    }
}

/// Writes an enum of named values (`Variant = "name",`), its `ALL` array,
/// its `number` (the value of the shader constant that selects it) and its
/// [`NamedOption`] impl. Attributes and doc comments of the enum and its
/// variants (`#[default]`) are kept.
#[macro_export]
#[doc(hidden)]
macro_rules! named_option {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $($(#[$variant_meta:meta])* $variant:ident = $text:literal,)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        $vis enum $name {
            $($(#[$variant_meta])* $variant,)+
        }

        impl $name {
            pub const ALL: [$name; [$($text),+].len()] = [$($name::$variant),+];

            /// The value of the shader constant that selects it.
            pub fn number(self) -> u32 {
                self as u32
            }
        }

        impl $crate::scene::NamedOption for $name {
            fn all() -> &'static [Self] {
                &Self::ALL
            }

            fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }
    };
}
pub use named_option;

#[cfg(test)]
mod tests {
    use super::NamedOption;
    use crate::scene::{TorusMethod, TriangleTest};

    /// Every value is found by its name, and a wrong name is answered
    /// with the list the command line shows.
    fn names_round_trip<T: NamedOption + PartialEq + std::fmt::Debug>(list: &str) {
        for &value in T::all() {
            assert_eq!(T::from_name(value.name()), Ok(value));
        }
        assert_eq!(T::from_name("nope"), Err(format!("one of {list}")));
    }

    #[test]
    fn options_are_chosen_by_their_names() {
        names_round_trip::<TriangleTest>("cramer, moller-trumbore, watertight");
        names_round_trip::<TorusMethod>("bisection, newton, closed-form");
        assert_eq!(TriangleTest::default(), TriangleTest::Watertight);
        assert_eq!(TorusMethod::default(), TorusMethod::Newton);
        assert_eq!(TorusMethod::Newton.number(), 1);
    }
}
