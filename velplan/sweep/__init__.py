"""Sweeps over designs: figures of merit of many variants, parameter grids and tolerance
Monte Carlo (`velplan sweep`)."""
