"""What the studies share: the cantilever's grid helpers, the references they compare against (the
continuum gold, the paper's and ABAQUS's numbers), the pendulum's cases."""
