"""The paper's reproduction: its tables and figures, and what they left open (the setting, the Yeoh cells,
the 2D assumption)."""
