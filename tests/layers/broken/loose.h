// A header in no layer.
