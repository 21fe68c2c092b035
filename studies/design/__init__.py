"""Element design: what an element's accuracy costs in time, what each effect costs, the timings."""
