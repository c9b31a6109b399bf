def multiblade_transform_matrices(*a, **k):
    raise NotImplementedError
