//! The configurations an rd table compares: their names, and what each
//! asks of the encoder and the decoder.
//!
//! A configuration turns (mesh, byte budget) into a `.swm` file that fits
//! the budget, or says that none does, that its encoder gave up, or that
//! it does not take the mesh at all. Adding one is a variant here, its
//! name, and the function its arm of `Config::run` calls (in `code`).
//! This file names the configurations only, so that the table, which
//! stores them, sits above it and below the code that runs them.

/// A way of coding a mesh into a byte budget. Rows sort in this order.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Config {
    /// swm's lossless mode alone: the input's triangles, at the largest qp
    /// (6..=24) whose file fits.
    Lossless,
    /// "Simplify, then lossless" (thesis Table 7-3): quadric edge collapse
    /// (swm's own) to the face count and qp (6..=16) with the lowest L2
    /// that fits (`swm encode --mode lossless --size B`).
    Baseline,
    /// `swm encode --effort max`: every method with its whole search
    /// (SwingWrapper, `baseline`, displaced subdivision, a method per
    /// component), whichever the encoder measures closer (`--mode
    /// auto`).
    Auto,
    /// `swm encode` with no flag (`--effort default`): `baseline`'s
    /// method, SwingWrapper where its retiling fits the level's work
    /// budget, and displaced subdivision at low rates, whichever the
    /// encoder measures closer.
    #[value(name = "auto-default")]
    AutoDefault,
    /// `swm encode --effort fast`: meshoptimizer's simplifier, then the
    /// lossless mode, with a short size search and no distance measured.
    #[value(name = "auto-fast")]
    AutoFast,
    /// SwingWrapper as `swm encode` runs it by default, asked for the
    /// budget and capped at it, decoded as `swm decode` does by default
    /// (following the file's post-processing hint).
    Swing,
    /// The `swing` file decoded plain, whatever its hint says.
    #[value(name = "swing-plain")]
    SwingPlain,
    /// `swing` with every tip on the input surface, as the thesis places
    /// them (the ablation of approximating tips).
    #[value(name = "swing-on-surface")]
    SwingOnSurface,
    /// `swing` with the edge length following the shape (adaptive
    /// sampling, `swm encode --adaptive`; not yet the default).
    #[value(name = "swing-adaptive")]
    SwingAdaptive,
    /// The `swing` file decoded with EdgeSharpener (no extra bits).
    #[value(name = "swing+sharpen")]
    SwingSharpen,
    /// The `swing` file decoded with EdgeSharpener and one Bender step.
    #[value(name = "swing+sharpen+bend")]
    SwingSharpenBend,
    /// Displaced subdivision alone (`swm encode --mode displaced`): a
    /// quadric-simplified base, levels of 1-to-4 subdivision, one scalar
    /// per new vertex; asked for the budget and capped at it.
    Displaced,
}

impl Config {
    /// Every configuration, in table order.
    pub const ALL: [Config; 12] = [
        Config::Lossless,
        Config::Baseline,
        Config::Auto,
        Config::AutoDefault,
        Config::AutoFast,
        Config::Swing,
        Config::SwingPlain,
        Config::SwingOnSurface,
        Config::SwingAdaptive,
        Config::SwingSharpen,
        Config::SwingSharpenBend,
        Config::Displaced,
    ];

    /// What `swm rd` runs without `--configs`: all but the ablation rows.
    pub fn default_set() -> Vec<Config> {
        Config::ALL
            .into_iter()
            .filter(|&c| !matches!(c, Config::SwingOnSurface | Config::SwingAdaptive))
            .collect()
    }

    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            Config::Lossless => "lossless",
            Config::Baseline => "baseline",
            Config::Auto => "auto",
            Config::AutoDefault => "auto-default",
            Config::AutoFast => "auto-fast",
            Config::Swing => "swing",
            Config::SwingPlain => "swing-plain",
            Config::SwingOnSurface => "swing-on-surface",
            Config::SwingAdaptive => "swing-adaptive",
            Config::SwingSharpen => "swing+sharpen",
            Config::SwingSharpenBend => "swing+sharpen+bend",
            Config::Displaced => "displaced",
        }
    }

    /// The effort level the automatic mode runs at (the table's `effort`
    /// column); `None` for configurations that do not run the automatic
    /// mode (they pin one method and its search).
    pub fn effort(self) -> Option<swm::Effort> {
        match self {
            Config::Auto => Some(swm::Effort::Max),
            Config::AutoDefault => Some(swm::Effort::Default),
            Config::AutoFast => Some(swm::Effort::Fast),
            _ => None,
        }
    }

    /// How the decoder post-processes this configuration's files.
    pub(super) fn decode_options(self) -> swm::DecodeOptions {
        let (sharpen, bend_steps) = match self {
            Config::SwingPlain => (Some(false), Some(0)),
            Config::SwingSharpen => (Some(true), Some(0)),
            Config::SwingSharpenBend => (Some(true), Some(1)),
            // The file's hint (the decoder's default).
            _ => (None, None),
        };
        swm::DecodeOptions {
            sharpen,
            bend_steps,
            ..Default::default()
        }
    }

    /// What this configuration asks of the SwingWrapper encoder.
    pub(super) fn tuning(self) -> swm::SwingTuning {
        swm::SwingTuning {
            approximate_tips: self != Config::SwingOnSurface,
            fit_tips: self != Config::SwingOnSurface,
            adaptive_density: self == Config::SwingAdaptive,
            front_contexts: true,
            loop_start: true,
            crease_tips: true,
            post_hint: true,
        }
    }

    /// The configuration a table names.
    pub fn from_name(name: &str) -> Option<Config> {
        Config::ALL.into_iter().find(|c| c.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::Config;
    use clap::ValueEnum;

    /// The command line and the tables must spell configurations alike.
    #[test]
    fn names_match_the_command_line() {
        for c in Config::ALL {
            let v = c.to_possible_value().expect("visible");
            assert_eq!(v.get_name(), c.name());
            assert_eq!(Config::from_name(c.name()), Some(c));
        }
        assert_eq!(Config::ALL.len(), Config::value_variants().len());
    }

    /// `auto` keeps the files it wrote before effort levels existed
    /// (`max`); each level has its configuration, named after it.
    #[test]
    fn each_effort_has_an_auto_configuration() {
        assert_eq!(Config::Auto.effort(), Some(swm::Effort::Max));
        for c in [Config::AutoDefault, Config::AutoFast] {
            let effort = c.effort().expect("an automatic configuration");
            assert_eq!(c.name(), format!("auto-{}", effort.name()));
        }
        assert_eq!(Config::Baseline.effort(), None);
        assert_eq!(Config::Swing.effort(), None);
    }
}
