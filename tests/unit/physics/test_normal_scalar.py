

def test_validity_warning_like_the_array_route():
    from contactlab.errors import ValidityWarning
    c = cl.Contact(Sphere(1e-3), (STEEL, STEEL))
    deep = 0.3e-3          # contact radius beyond R/2
    with pytest.warns(ValidityWarning):
        c.normal(depth=np.array([deep]))
    with pytest.warns(ValidityWarning) as rec:
        c.normal(depth=deep)
    assert rec[0].filename == __file__        # points at the caller
