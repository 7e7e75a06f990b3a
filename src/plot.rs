//! Charts as SVG files (plotters): the pressure chart of a solution, for slides and papers.
