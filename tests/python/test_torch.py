"""The PyTorch bridge: energies and a model's forward as autograd Functions, checked against finite
differences with torch.autograd.gradcheck."""
import numpy as np
import pytest

torch = pytest.importorskip("torch", reason="PyTorch is not installed (Debian: python3-torch)")

import drape  # noqa: E402
import drape.torch_bridge as dt  # noqa: E402
from conftest import CONTACT, TINY_GRAPH  # noqa: E402


@pytest.fixture(scope="module")
def scene():
    return drape.Scene(str(CONTACT))


@pytest.fixture(scope="module")
def state(scene):
    """The dressed garment moved a little, on the mean body (clear of it: the barrier is finite)."""
    noise = np.random.default_rng(0).normal(scale=5e-4, size=scene.garment_vertices.shape)
    return torch.tensor(np.array(scene.garment_vertices) + noise, dtype=torch.float64)


def test_every_energy_passes_gradcheck(scene, state):
    energies = scene.energies(np.array(scene.mean_body))
    assert list(energies) == ["gravity", "stretching", "bending", "barrier", "self_contact", "collision"]
    rng = np.random.default_rng(1)
    for name, e in energies.items():
        x = state.clone().requires_grad_(True)
        # Every coordinate at once along random directions (fast mode) ...
        assert torch.autograd.gradcheck(lambda x: dt.energy(x, e), (x,), eps=1e-6, atol=1e-6, rtol=1e-4,
                                        fast_mode=True), name
        # ... and coordinate by coordinate on a few vertices, with steps of 1e-8 m: ArcSim's
        # stiffness lookup is C1 with narrow smoothing bands (1e-3 of shear), across which the
        # stretching gradient turns fast enough that 1e-6 m differences miss it by 3e-4
        # (differences of 1e-8 m agree with it to 1e-7).
        rows = torch.from_numpy(rng.choice(len(state), 8, replace=False))
        free = state[rows].clone().requires_grad_(True)
        assert torch.autograd.gradcheck(lambda v: dt.energy(state.index_put((rows,), v), e), (free,), eps=1e-8,
                                        atol=1e-6, rtol=1e-4), name


def test_scene_energy_is_the_sum_and_batches(scene, state):
    physics = dt.SceneEnergy(scene, np.array(scene.mean_body))
    x = state.clone().requires_grad_(True)
    total = physics(x)
    expected = sum(e.value(state.numpy()) for e in physics.energies.values())
    assert total.item() == pytest.approx(expected, rel=1e-12)
    total.backward()
    expected_grad = sum(e.gradient(state.numpy()) for e in physics.energies.values())
    np.testing.assert_allclose(x.grad.numpy(), expected_grad, rtol=1e-12, atol=1e-12)
    batch = torch.stack([state, state + 1e-4])
    values = physics(batch)
    assert values.shape == (2,) and values[0].item() == pytest.approx(expected, rel=1e-12)
    # float32 in, float32 out; drape still computes in double.
    assert physics(state.float()).dtype == torch.float32
    with pytest.raises(ValueError, match="no effect 'wind'"):
        dt.SceneEnergy(scene, names=["wind"])


@pytest.fixture(scope="module")
def tiny_model():
    return drape.Model.untrained(TINY_GRAPH, {"resolution": "coarse"}, seed=1)


@pytest.mark.filterwarnings("ignore:Input #0 requires gradient and is not a double")
def test_model_forward_passes_gradcheck(tiny_model):
    net = dt.DrapeModel(tiny_model)
    body = torch.from_numpy(tiny_model.body(bmi=35))
    weights = net.named_drape_weights()
    names = list(weights)
    picked = torch.from_numpy(np.random.default_rng(2).choice(3 * tiny_model.garment_vertex_count, 24, replace=False))
    for name in names:
        def f(w, name=name):
            args = [w if n == name else weights[n].detach() for n in names]
            return dt.ModelFunction.apply(body, tiny_model, names, *args).reshape(-1)[picked]
        w = weights[name].detach().clone().requires_grad_(True)
        # The network is float32: a wider step and looser tolerances than the energies' double.
        assert torch.autograd.gradcheck(f, (w,), eps=1e-3, atol=1e-3, rtol=1e-2, fast_mode=w.numel() > 100), name
    # The weights are back as they were: the module predicts what drape.Model.predict does.
    np.testing.assert_allclose(net(body).detach().numpy(), tiny_model.predict(body.numpy()), atol=1e-6)


def test_parameters_are_drapes_weights_and_a_torch_loop_trains_them():
    model = drape.Model.untrained(TINY_GRAPH, {"resolution": "coarse"}, seed=3)
    net = dt.DrapeModel(model)
    body = torch.from_numpy(model.body(bmi=30))
    first = next(iter(net.parameters()))
    with torch.no_grad():
        first += 0.5  # changes drape's own weights: no copy in between
    np.testing.assert_array_equal(model.weights()[next(iter(model.weights()))], first.detach().numpy())
    np.testing.assert_allclose(net(body).detach().numpy(), model.predict(body.numpy()), atol=1e-6)
    target = torch.from_numpy(np.array(model.assets.garment_vertices, dtype=np.float32)) + 0.01
    opt = torch.optim.Adam(net.parameters(), lr=1e-2)
    losses = []
    for _ in range(20):
        opt.zero_grad()
        loss = ((net(body) - target) ** 2).mean()
        loss.backward()
        opt.step()
        losses.append(loss.item())
    assert losses[-1] < 0.2 * losses[0]


def test_a_weight_changed_in_place_before_backward_raises_and_integer_vertices_are_refused(scene, state):
    # An in-place change between forward and backward gave a gradient that was neither the forward's nor the
    # new weights' (the saved weights were detach()ed aliases); torch's modules raise, and so does this.
    model = drape.Model.untrained(TINY_GRAPH, {"resolution": "coarse"}, seed=4)
    net = dt.DrapeModel(model)
    body = torch.from_numpy(model.body(bmi=30))
    loss = net(body).square().sum()
    with torch.no_grad():
        next(iter(net.parameters())).mul_(2.0)
    with pytest.raises(RuntimeError, match="modified by an inplace operation"):
        loss.backward()
    # And through drape's own memory, which bumps no torch version counter.
    loss = net(body).square().sum()
    model.weights()[next(iter(model.weights()))][...] += 0.5  # (a bias starts at zero: add, not scale)
    with pytest.raises(RuntimeError, match="changed in place between this forward and its backward"):
        loss.backward()
    # A weight that is NaN (a diverged training) is no change (NaN equals itself bit for bit): what is said is
    # the garment's NaN, not "changed in place".
    with torch.no_grad():
        next(iter(net.parameters())).fill_(float("nan"))
    with pytest.raises(ValueError, match="grad_garment: non-finite coordinate"):
        net(body).square().sum().backward()
    # Integer vertices: one ValueError naming the argument and the dtype (they were converted silently and
    # refused for what followed).
    with pytest.raises(ValueError, match=r"body: expected floating-point vertices in metres, got torch.int64"):
        net(body.long())
    with pytest.raises(ValueError, match=r"x: expected floating-point vertices in metres, got torch.int64"):
        dt.SceneEnergy(scene)(state.long())
    with pytest.raises(ValueError, match=r"body: expected floating-point vertices in metres, got int64"):
        net(body.numpy().astype(np.int64))
